#pragma once
// Effort drift: the offset of the measured effort creeps as motors and
// amplifiers warm up. A bias calibrated at the start of a session is then
// wrong later, and the error reads as a phantom external torque.

#include <cmath>
#include <string>
#include <vector>

#include "pliant/models/effect.h"

namespace pliant::models {

/// tau_j = a_j·(1 − exp(−t / T)) (N·m), t the log time: a first-order thermal
/// settling from the start of the log to the offset a_j with time constant T.
/// Parameters: drift1, drift2 (N·m), time_constant (s). Defaults: no drift.
class EffortDriftEffect {
 public:
  static constexpr EffectInfo kInfo{
      "effort_drift", Channel::kInternalTorque,
      "the effort offset creeps as the motors warm: a_j·(1 − exp(−t/T)) added to the bias"};

  std::vector<ParameterSpec> Parameters() const;

  template <typename T>
  Vec2<T> operator()(const T* p, const JointState<T>& state) const {
    using std::exp;
    const T settled = T(1.0) - exp(-state.time_s / p[2]);
    return {p[0] * settled, p[1] * settled};
  }
};

}  // namespace pliant::models
