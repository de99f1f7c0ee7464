#pragma once
// Effort delay: the effort samples lag the encoder samples (the current
// loop's filter, the amplifier's read-out, a bus cycle). While the load
// changes, the effort logged with an encoder sample is the load of a moment
// earlier, and the model reads the difference as deflection.

#include <string>
#include <vector>

#include "pliant/models/effect.h"

namespace pliant::models {

/// tau_j = −d·dtau_meas_j/dt (N·m): to first order in the delay d,
/// tau_meas(t) = tau(t − d) ≈ tau(t) − d·tau̇. Needs JointState::effort_rate_nm_s
/// (the diagnosis estimates it from the log by a local linear fit).
/// Parameter: delay (s). Default: none.
class EffortDelayEffect {
 public:
  static constexpr EffectInfo kInfo{
      "effort_delay", Channel::kInternalTorque,
      "the effort samples lag the encoder samples by d: while the load changes the effort "
      "reads −d·dtau/dt off"};

  std::vector<ParameterSpec> Parameters() const;

  template <typename T>
  Vec2<T> operator()(const T* p, const JointState<T>& state) const {
    return {-p[0] * state.effort_rate_nm_s[0], -p[0] * state.effort_rate_nm_s[1]};
  }
};

}  // namespace pliant::models
