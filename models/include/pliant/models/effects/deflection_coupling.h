#pragma once
// Deflection coupling between the two lateral directions: a pitch load bends
// the shaft a little toward yaw and vice versa (the shaft's principal axes and
// the arm's double parallelogram are not aligned with the joint axes). The
// paper treats the two joints independently.

#include <string>
#include <vector>

#include "pliant/models/effect.h"

namespace pliant::models {

/// Deflection (k12·tau_ext_2, k21·tau_ext_1) (rad).
/// Parameters: k12, k21 (rad/(N·m)). Defaults: uncoupled.
class DeflectionCouplingEffect {
 public:
  static constexpr EffectInfo kInfo{
      "deflection_coupling", Channel::kDeflection,
      "a load on one joint bends the shaft a little along the other: k12·tau2 on joint 1, "
      "k21·tau1 on joint 2"};

  std::vector<ParameterSpec> Parameters() const;

  template <typename T>
  Vec2<T> operator()(const T* k, const JointState<T>& state) const {
    return {k[0] * state.external_torque_nm[1], k[1] * state.external_torque_nm[0]};
  }
};

}  // namespace pliant::models
