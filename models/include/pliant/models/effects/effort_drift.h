#pragma once
// Effort drift: the offset of the measured effort creeps as motors and
// amplifiers warm up. A bias calibrated at the start of a session is then
// wrong later, and the error reads as a phantom external torque.

#include <cmath>
#include <string>
#include <vector>

#include "pliant/models/effect.h"

namespace pliant::models {

/// tau_j = r_j·(1 − exp(−k·t)) / k (N·m), t the log time: a first-order
/// thermal settling that starts at the rate r_j (N·m/s) and levels off at
/// r_j / k with settling rate k = 1/T (1/s). It is written by the initial rate
/// and 1/T, not by the final offset and T, so that a creep that has not yet
/// levelled off within the log (k → 0: tau = r·t, linear) lies inside the
/// parameter space instead of at the end of a ridge where offset and T grow
/// together without bound.
/// Parameters: rate1, rate2 (N·m/s), settling_rate (1/s). Defaults: no drift.
class EffortDriftEffect {
 public:
  static constexpr EffectInfo kInfo{
      "effort_drift", Channel::kInternalTorque,
      "the effort offset creeps as the motors warm: r_j·(1 − exp(−k·t))/k added to the bias "
      "(linear r_j·t while k·t is small)"};

  std::vector<ParameterSpec> Parameters() const;

  template <typename T>
  Vec2<T> operator()(const T* p, const JointState<T>& state) const {
    using std::expm1;
    const T kt = p[2] * state.time_s;
    // (1 − e^(−kt))/k, its series where kt is too small to divide by k.
    const T elapsed = kt < T(1e-6) ? state.time_s * (T(1.0) - kt / T(2.0))
                                   : -expm1(-kt) / p[2];
    return {p[0] * elapsed, p[1] * elapsed};
  }
};

}  // namespace pliant::models
