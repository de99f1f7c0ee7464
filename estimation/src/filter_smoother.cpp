#include "pliant/estimation/filter_smoother.h"

#include <cmath>

#include <Eigen/Cholesky>

namespace pliant::estimation {
namespace {

constexpr int kTorque = kStateTorque, kBacklash = kStateBacklash, kScale = kStateScale,
              kClearance = kStateClearance, kOffset = kStateEffortOffset;
using Matrix = FilterStateMatrix;

// F·M for the transition's F: the identity but for β's diagonal (ρ), tau's row
// (∂tau+/∂tau, ∂tau+/∂s) and b's (∂b+/∂tau, ∂b+/∂b, ∂b+/∂e), so only those
// three rows change.
Matrix TransitionTimes(const FilterTransition& t, const Matrix& m) {
  Matrix out = m;
  out.row(kTorque) = t.f_torque_torque * m.row(kTorque) + t.f_torque_scale * m.row(kScale);
  out.row(kBacklash) = t.f_backlash_torque * m.row(kTorque) +
                       t.f_backlash_backlash * m.row(kBacklash) +
                       t.f_backlash_clearance * m.row(kClearance);
  out.row(kOffset) = t.f_offset_offset * m.row(kOffset);
  return out;
}

// F·B(P)·Fᵀ + Q with B the seating bound (as the filter predicts). B(P) − P
// acts as process noise added at k, so the smoother's cross-covariance stays
// P·Fᵀ.
Matrix Predicted(const Matrix& p, const FilterTransition& t) {
  Matrix bounded = p;
  SeatingBound(&bounded, t.seating_bound_weight);
  const Matrix f_bounded = TransitionTimes(t, bounded);
  Matrix out = TransitionTimes(t, f_bounded.transpose());  // F·(F·B)ᵀ = F·B·Fᵀ, B symmetric
  out.diagonal() += t.process_noise;
  return out;
}

}  // namespace

SmootherStep RecordStep(const ComplianceFilter& filter, double previous_depth_m, bool first) {
  SmootherStep record;
  for (int j = 0; j < 2; ++j) {
    record.state[j] = filter.joint_state(j);
    record.transition[j] = filter.transition(j);
  }
  const FilterSample& sample = filter.state_sample();
  const FilterEstimate& estimate = filter.state_estimate();
  record.encoder_rad = sample.encoder_rad;
  record.depth_m = std::isfinite(sample.insertion_depth_m) || first ? sample.insertion_depth_m
                                                                     : previous_depth_m;
  record.nis = estimate.nis;
  record.nis_dof = estimate.nis_dof;
  record.flags = estimate.flags;
  return record;
}

void SmoothStep(SmootherStep* here, const SmootherStep& next) {
  for (int j = 0; j < 2; ++j) {
    const FilterTransition& transition = next.transition[j];
    if (!transition.predicted) continue;  // a restart: nothing links k to k+1
    FilterJointState& state = here->state[j];
    const Matrix p_pred = Predicted(state.covariance, transition);
    // C = P̂ Fᵀ (P⁻)⁻¹ = ((P⁻)⁻¹ F P̂)ᵀ, P⁻ and P̂ symmetric. Solved a column at
    // a time: Eigen's solve with a 6×6 right-hand side takes its blocked
    // (dynamic-size) path, slower at this size.
    const Eigen::LDLT<Matrix> factor(p_pred);
    Matrix solved = TransitionTimes(transition, state.covariance);
    for (int c = 0; c < kFilterJointStates; ++c) {
      solved.col(c) = factor.solve(solved.col(c).eval());
    }
    const Matrix gain = solved.transpose();
    state.mean += gain * (next.state[j].mean - transition.predicted_mean);
    state.covariance += gain * (next.state[j].covariance - p_pred) * gain.transpose();
    state.covariance = 0.5 * (state.covariance + state.covariance.transpose()).eval();
  }
}

FilterEstimate StepEstimate(const SmootherStep& r) {
  FilterEstimate e = MakeEstimate(r.state[0], r.state[1], r.encoder_rad, r.depth_m);
  e.nis = r.nis;
  e.nis_dof = r.nis_dof;
  e.flags = r.flags;
  return e;
}

FilterSmoother::FilterSmoother(const models::ModelParameters& parameters,
                               const FilterOptions& options)
    : filter_(parameters, options) {}

void FilterSmoother::Reserve(std::size_t samples) { steps_.reserve(samples); }

FilterEstimate FilterSmoother::Add(const FilterSample& sample) {
  const FilterEstimate estimate = filter_.Step(sample);
  if (filter_.advanced()) Record();
  smoothed_ = false;
  return estimate;
}

// One record per sample the filter's state has reached (with motor inertia
// it runs alignment_steps() behind Add's newest).
void FilterSmoother::Record() {
  const bool first = steps_.empty();
  steps_.push_back(RecordStep(filter_, first ? 0.0 : steps_.back().depth_m, first));
}

void FilterSmoother::Smooth() {
  while (filter_.StepHeldSample()) Record();  // the log's last samples
  if (smoothed_ || steps_.size() < 2) {
    smoothed_ = true;
    return;
  }
  for (std::size_t k = steps_.size() - 1; k-- > 0;) SmoothStep(&steps_[k], steps_[k + 1]);
  smoothed_ = true;
}

}  // namespace pliant::estimation
