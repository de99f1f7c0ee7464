// The inertial alignment (FilterOptions::align_inertial_torque): with motor
// inertia the filter's state runs alignment_steps samples behind the newest,
// so that each effort meets the J·θ̈ it holds, which the acceleration fit
// gives only that late. The motor's motion follows the newest sample; Output
// carries the state's estimate to it and applies the output step limit.
#include <cmath>

#include "filter_impl.h"

namespace pliant::estimation {

using namespace filter_internal;

// The motor's acceleration follows the newest sample; the state may run
// alignment_steps behind it (FilterOptions::align_inertial_torque).
FilterEstimate ComplianceFilter::Impl::Step(const FilterSample& sample) {
  AdvanceMotion(sample);
  advanced = false;
  if (!initialised) {
    StepState(sample);
  } else {
    held[(held_first + held_count) % kHeldCapacity] = sample;
    ++held_count;
    if (held_count > alignment_steps) StepHeldSample();
  }
  return Output(sample);
}

bool ComplianceFilter::Impl::StepHeldSample() {
  if (held_count == 0) return false;
  const int oldest = held_first;
  held_first = (held_first + 1) % kHeldCapacity;
  --held_count;
  StepState(held[oldest]);  // the slot is not written again before the next Step
  return true;
}

void ComplianceFilter::Impl::AdvanceMotion(const FilterSample& sample) {
  newest_step.setZero();
  if (!motion_started) {
    motion_started = true;
    motion_clock.Start(sample);
    // A log begun mid-motion: the tracker starts at the log's own velocity
    // where it has one, not at rest (from rest its J·θ̈ swung by N·m for tens
    // of milliseconds and read a contact, experiments/second_generator/arm.py).
    for (int j = 0; j < 2; ++j)
      if (std::isfinite(sample.velocity_rad_s[j])) motion[j].velocity_rad_s = sample.velocity_rad_s[j];
    return;
  }
  bool implausible[2];
  const double dt = motion_clock.Advance(sample, options.sample_period_s, &newest_step, implausible);
  for (int j = 0; j < 2; ++j) motion[j].Advance(options, dt, newest_step[j]);
}

// The state's estimate, carried to the newest sample when the state runs
// behind it, then held to the output step limit.
FilterEstimate ComplianceFilter::Impl::Output(const FilterSample& newest) {
  FilterEstimate estimate = state_estimate;
  const double newest_depth = std::isfinite(newest.insertion_depth_m) ? newest.insertion_depth_m : depth;
  if (held_count > 0) CarryEstimate(state_sample, newest, newest_depth, &estimate);
  // The limit serves a held tip, whose estimate jumps when the shaft meets its
  // wall; without the tip_fixed hint the estimate is the contact chain's
  // collapse, and a limited output lagged it by tens of mrad for seconds on
  // the real free-motion bag (docs/decisions/output-step-limit.md).
  if (options.infer_contact && !newest.tip_fixed) restart_output[0] = restart_output[1] = true;
  const Eigen::Vector2d limit =
      newest_step.cwiseAbs().array() + options.output_step_limit_counts * output_count_rad;
  limiter.Apply(limit, restart_output, newest.encoder_rad, newest_depth, &estimate);
  restart_output[0] = restart_output[1] = false;
  return estimate;
}

}  // namespace pliant::estimation
