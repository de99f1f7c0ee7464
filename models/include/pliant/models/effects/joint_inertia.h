#pragma once
// Joint inertia: the effort that accelerates the arm. The paper's model is
// quasi-static and has none; on a real PSM it is most of what a free arm's
// effort holds beyond the bias table while it moves (docs/real-data.md), and
// an estimator that does not know it reads it as load.

#include <string>
#include <vector>

#include "pliant/models/effect.h"

namespace pliant::models {

/// tau_j = J_j · a_j (N·m), a_j the joint's acceleration (rad/s²;
/// JointState::acceleration_rad_s2). Parameters: inertia1, inertia2 (kg·m²,
/// motor, capstan and links as the joint's effort sees them). Defaults: none.
/// The simulator's plant carries its arm's inertia in its dynamics
/// (scenario `joint.inertia_kg_m2`), not as this effect.
class JointInertiaEffect {
 public:
  static constexpr EffectInfo kInfo{
      "joint_inertia", Channel::kInternalTorque,
      "the effort accelerates the arm: J·a, which shows in the effort only while a joint "
      "speeds up or slows down; fitted from free motion"};

  std::vector<ParameterSpec> Parameters() const;

  template <typename T>
  Vec2<T> operator()(const T* p, const JointState<T>& state) const {
    return Vec2<T>(p[0] * state.acceleration_rad_s2[0], p[1] * state.acceleration_rad_s2[1]);
  }
};

}  // namespace pliant::models
