#pragma once
// Cross-joint bias torque: the counterbalance and gravity load of one joint
// depend on the other joint's angle too (the pitch parallelogram's weight
// swings with yaw; the yaw axis carries a moment that changes with pitch).
// The paper's tau0_j is a function of joint j's own angle only.

#include <cmath>
#include <string>
#include <vector>

#include "pliant/models/effect.h"

namespace pliant::models {

/// tau_1 = c1·sin(q2), tau_2 = c2·sin(q1) (N·m): the first harmonic of the
/// other joint's angle, zero at the calibration pose q = 0.
/// Parameters: cross1, cross2 (N·m). Defaults: none.
class BiasTorqueCrossJointEffect {
 public:
  static constexpr EffectInfo kInfo{
      "bias_torque_cross_joint", Channel::kInternalTorque,
      "each joint's bias also depends on the other joint's angle (the arm's weight swings with "
      "it): c1·sin(q2) on joint 1, c2·sin(q1) on joint 2"};

  std::vector<ParameterSpec> Parameters() const;

  template <typename T>
  Vec2<T> operator()(const T* c, const JointState<T>& state) const {
    using std::sin;
    return {c[0] * sin(state.encoder_angle_rad[1]), c[1] * sin(state.encoder_angle_rad[0])};
  }
};

}  // namespace pliant::models
