#include "pliant/estimation/effect_inputs.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include "pliant/estimation/extra_effects.h"

namespace pliant::estimation {

EffectInputs::EffectInputs(bool quasi_static, double max_step_s, double effort_rate_window_s)
    : quasi_static_(quasi_static), max_step_s_(max_step_s), window_s_(effort_rate_window_s) {}

const models::JointState<double>& EffectInputs::Update(double time_s, const Eigen::Vector3d& q,
                                                       const Eigen::Vector2d& effort_nm,
                                                       const Eigen::Vector2d& velocity_rad_s) {
  state_.encoder_angle_rad = q.head<2>();
  state_.insertion_depth_m = q[2];
  state_.time_s = time_s;
  state_.external_torque_nm.setZero();
  state_.travel_since_reversal_rad = travel_.Update(state_.encoder_angle_rad);
  const double dt = time_s - last_time_;  // NaN on the first row
  const bool pose = quasi_static_ || dt > max_step_s_;
  for (int j = 0; j < 2; ++j) {
    double v = velocity_rad_s[j];
    if (!std::isfinite(v)) v = dt > 0.0 ? (q[j] - last_angle_[j]) / dt : 0.0;
    state_.velocity_rad_s[j] = pose || !std::isfinite(v) ? 0.0 : v;
  }
  last_time_ = time_s;
  last_angle_ = q.head<2>();
  state_.effort_rate_nm_s.setZero();
  state_.acceleration_rad_s2.setZero();
  if (pose) {  // the rate's window starts again after a gap
    count_ = 0;
    Resum();
  }
  if (quasi_static_ || !std::isfinite(time_s)) return state_;
  AddEffort(time_s, effort_nm, state_.velocity_rad_s);
  // The least-squares slopes of the window's efforts and velocities against time.
  const double denominator = n_ * stt_ - st_ * st_;
  if (n_ >= 3.0 && denominator > 0.0) {
    const auto slope = [&](int k) { return (n_ * sty_[k] - st_ * sy_[k]) / denominator; };
    for (int j = 0; j < 2; ++j) {
      state_.effort_rate_nm_s[j] = slope(j);
      state_.acceleration_rad_s2[j] = slope(2 + j);
    }
  }
  return state_;
}

const models::JointState<double>& EffectInputs::Update(const io::StandardColumns& c,
                                                       const double* row) {
  const auto value = [row](int column) {
    return column >= 0 ? row[column] : std::numeric_limits<double>::quiet_NaN();
  };
  return Update(value(c.t), Eigen::Vector3d(value(c.q1), value(c.q2), value(c.q3)),
                Eigen::Vector2d(value(c.tau1), value(c.tau2)),
                Eigen::Vector2d(value(c.v1), value(c.v2)));
}

void EffectInputs::AddEffort(double time_s, const Eigen::Vector2d& measured_nm,
                             const Eigen::Vector2d& velocity_rad_s) {
  // Time going back (another log, a restart) or no effort at all: start again.
  const bool back = count_ > 0 && time_s < time_[(oldest_ + count_ - 1) % kRing];
  const bool none = !std::isfinite(measured_nm[0]) && !std::isfinite(measured_nm[1]);
  if (back || none) {
    count_ = 0;
    Resum();
    if (none) return;
  }
  // One joint without a sample (a single-joint log, a dropped value) repeats
  // its last: the other joint's rate goes on.
  Eigen::Vector2d effort_nm;
  for (int j = 0; j < 2; ++j) {
    if (std::isfinite(measured_nm[j])) last_effort_[j] = measured_nm[j];
    effort_nm[j] = last_effort_[j];
  }
  if (count_ == 0) anchor_s_ = time_s;  // (an epoch's seconds would cancel in the sums)
  if (count_ == kRing) DropOldest();  // the ring is full
  const int slot = (oldest_ + count_) % kRing;
  time_[slot] = time_s;
  for (int j = 0; j < 2; ++j) {
    value_[j][slot] = effort_nm[j];
    value_[2 + j][slot] = velocity_rad_s[j];
  }
  ++count_;
  Sum(slot, 1.0);
  while (count_ > 1 && time_[oldest_] < time_s - window_s_) DropOldest();
  if (++since_resum_ >= kRing) Resum();
}

void EffectInputs::DropOldest() {
  Sum(oldest_, -1.0);
  oldest_ = (oldest_ + 1) % kRing;
  --count_;
}

// Adds (sign 1) or takes out (−1) one row's share of the rate line's sums.
void EffectInputs::Sum(int slot, double sign) {
  const double t = time_[slot] - anchor_s_;
  n_ += sign, st_ += sign * t, stt_ += sign * t * t;
  for (int k = 0; k < kChannels; ++k) {
    sy_[k] += sign * value_[k][slot];
    sty_[k] += sign * t * value_[k][slot];
  }
}

// The sums from the ring itself, about its oldest time.
void EffectInputs::Resum() {
  since_resum_ = 0;
  anchor_s_ = count_ > 0 ? time_[oldest_] : 0.0;
  n_ = st_ = stt_ = 0.0;
  for (int k = 0; k < kChannels; ++k) sy_[k] = sty_[k] = 0.0;
  for (int k = 0; k < count_; ++k) Sum((oldest_ + k) % kRing, 1.0);
}

// The stream's trailing line (EffectInputs) read half a window later, at the
// last row of the same stretch (no gap) no later than t + w/2: the fit has the
// whole log, and the centred line finds an effort delay's physical value where
// the trailing one, w/2 late, finds less (decision record effect-inputs.md).
namespace {

std::vector<Eigen::Vector2d> Centred(const io::Log& log, double window_s, double max_step_s,
                                     Eigen::Vector2d models::JointState<double>::*input) {
  const std::size_t n = log.Rows();
  std::vector<Eigen::Vector2d> trailing(n), centred(n, Eigen::Vector2d::Zero());
  if (log.header.QuasiStatic()) return centred;
  const io::StandardColumns c(log.header);
  std::vector<bool> starts(n, true);  // the first row of a stretch
  EffectInputs tracker(false, max_step_s, window_s);
  for (std::size_t r = 0; r < n; ++r) {
    trailing[r] = tracker.Update(c, &log.values[r * log.Columns()]).*input;
    const double dt = r > 0 ? log.Value(r, c.t) - log.Value(r - 1, c.t) : -1.0;
    starts[r] = !(dt >= 0.0 && dt <= max_step_s);
  }
  std::size_t k = 0;
  for (std::size_t r = 0; r < n; ++r) {
    k = std::max(k, r);
    const double until = log.Value(r, c.t) + 0.5 * window_s;
    while (k + 1 < n && !starts[k + 1] && log.Value(k + 1, c.t) <= until) ++k;
    centred[r] = trailing[k];
  }
  return centred;
}

}  // namespace

std::vector<Eigen::Vector2d> CentredEffortRates(const io::Log& log, double window_s,
                                                double max_step_s) {
  return Centred(log, window_s, max_step_s, &models::JointState<double>::effort_rate_nm_s);
}

std::vector<Eigen::Vector2d> CentredAccelerations(const io::Log& log, double window_s,
                                                  double max_step_s) {
  return Centred(log, window_s, max_step_s, &models::JointState<double>::acceleration_rad_s2);
}

io::Log WithoutInternalTorque(const io::Log& log, const models::ModelParameters& parameters) {
  io::Log out = log;
  const ExtraEffects effects(parameters.effects);
  if (effects.empty()) return out;
  const io::StandardColumns c(log.header);
  EffectInputs inputs(log.header.QuasiStatic());
  // As the effects were fitted beside it: the effort's rate and the acceleration centred.
  const std::vector<Eigen::Vector2d> rate = CentredEffortRates(log);
  const std::vector<Eigen::Vector2d> acceleration = CentredAccelerations(log);
  for (std::size_t r = 0; r < log.Rows(); ++r) {
    models::JointState<double> state = inputs.Update(c, &log.values[r * log.Columns()]);
    state.effort_rate_nm_s = rate[r];
    state.acceleration_rad_s2 = acceleration[r];
    const Eigen::Vector2d internal = effects.InternalTorque(state);
    const int tau[2] = {c.tau1, c.tau2};
    for (int j = 0; j < 2; ++j) {
      if (std::isfinite(internal[j])) out.values[r * log.Columns() + std::size_t(tau[j])] -= internal[j];
    }
  }
  return out;
}

}  // namespace pliant::estimation
