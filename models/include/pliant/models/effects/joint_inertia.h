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

/// The arm's inertia between joints 1 and 2, the mass matrix's off-diagonal
/// M12: tau_1 = J12 · a_2 and tau_2 = J12 · a_1 (N·m), symmetric as a mass
/// matrix is. Parameter: inertia12 (kg·m²). Defaults: none. Where the two
/// joints speed up together, a fit of the diagonal alone takes M12 into J1
/// and J2 (another arm's free motion: J1 −21 % at 6.8 σ with M12 8 % of J1).
class JointInertiaCouplingEffect {
 public:
  static constexpr EffectInfo kInfo{
      "joint_inertia_coupling", Channel::kInternalTorque,
      "one joint's acceleration takes effort at the other: J12·a of the other joint (the arm's "
      "mass matrix off its diagonal); fitted from free motion"};

  std::vector<ParameterSpec> Parameters() const;

  template <typename T>
  Vec2<T> operator()(const T* p, const JointState<T>& state) const {
    return Vec2<T>(p[0] * state.acceleration_rad_s2[1], p[0] * state.acceleration_rad_s2[0]);
  }
};

}  // namespace pliant::models
