#include "pliant/estimation/filter_smoother.h"

#include <cmath>

#include <Eigen/Cholesky>

namespace pliant::estimation {
namespace {

constexpr int kTorque = kStateTorque, kBacklash = kStateBacklash, kScale = kStateScale,
              kClearance = kStateClearance;
using Matrix = FilterStateMatrix;

Matrix TransitionMatrix(const FilterTransition& t) {
  Matrix f = Matrix::Identity();
  f(kTorque, kTorque) = t.f_torque_torque;
  f(kTorque, kScale) = t.f_torque_scale;
  f(kBacklash, kTorque) = t.f_backlash_torque;
  f(kBacklash, kBacklash) = t.f_backlash_backlash;
  f(kBacklash, kClearance) = t.f_backlash_clearance;
  return f;
}

// F·B(P)·Fᵀ + Q with F = I but for b's row and tau's, B the seating bound
// (as the filter predicts). B(P) − P acts as process noise added at k, so the
// smoother's cross-covariance stays P·Fᵀ.
Matrix Predicted(const Matrix& p, const FilterTransition& t) {
  const Matrix f = TransitionMatrix(t);
  Matrix bounded = p;
  SeatingBound(&bounded, t.seating_bound_weight);
  Matrix out = f * bounded * f.transpose();
  out.diagonal() += t.process_noise;
  return out;
}

}  // namespace

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
  StepRecord record;
  for (int j = 0; j < 2; ++j) {
    record.joint[j].state = filter_.joint_state(j);
    record.joint[j].transition = filter_.transition(j);
  }
  const FilterSample& sample = filter_.state_sample();
  const FilterEstimate& estimate = filter_.state_estimate();
  record.encoder_rad = sample.encoder_rad;
  record.depth_m = std::isfinite(sample.insertion_depth_m) || steps_.empty()
                       ? sample.insertion_depth_m
                       : steps_.back().depth_m;
  record.nis = estimate.nis;
  record.nis_dof = estimate.nis_dof;
  record.flags = estimate.flags;
  steps_.push_back(record);
}

void FilterSmoother::Smooth() {
  while (filter_.StepHeldSample()) Record();  // the log's last samples
  if (smoothed_ || steps_.size() < 2) {
    smoothed_ = true;
    return;
  }
  for (std::size_t k = steps_.size() - 1; k-- > 0;) {
    for (int j = 0; j < 2; ++j) {
      const JointRecord& next = steps_[k + 1].joint[j];
      if (!next.transition.predicted) continue;  // a restart: nothing links k to k+1
      FilterJointState& here = steps_[k].joint[j].state;
      const Matrix p_pred = Predicted(here.covariance, next.transition);
      const Matrix f = TransitionMatrix(next.transition);
      // C = P̂ Fᵀ (P⁻)⁻¹ = ((P⁻)⁻¹ F P̂)ᵀ, P⁻ and P̂ symmetric.
      const Matrix gain = p_pred.ldlt().solve(f * here.covariance).transpose();
      here.mean += gain * (next.state.mean - next.transition.predicted_mean);
      here.covariance += gain * (next.state.covariance - p_pred) * gain.transpose();
      here.covariance = 0.5 * (here.covariance + here.covariance.transpose()).eval();
    }
  }
  smoothed_ = true;
}

FilterEstimate FilterSmoother::Estimate(std::size_t k) const {
  const StepRecord& r = steps_.at(k);
  FilterEstimate e = MakeEstimate(r.joint[0].state, r.joint[1].state, r.encoder_rad, r.depth_m);
  e.nis = r.nis;
  e.nis_dof = r.nis_dof;
  e.flags = r.flags;
  return e;
}

}  // namespace pliant::estimation
