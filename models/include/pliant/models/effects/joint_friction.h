#pragma once
// Joint friction: the drive (motor, capstan, cables) resists motion. The
// paper's quasi-static model has no such term; it shows in the effort only
// while a joint moves.

#include <cmath>
#include <string>
#include <vector>

#include "pliant/models/effect.h"

namespace pliant::models {

/// tau_j = b_j·v_j + F_j·tanh(v_j / v_s) (N·m): viscous friction plus a Coulomb
/// level smoothed over the velocity scale v_s, so that it stays differentiable
/// (and gives no stiction: at rest it vanishes).
/// Parameters: viscous1, viscous2 (N·m·s/rad), coulomb1, coulomb2 (N·m),
/// velocity_scale (rad/s). Defaults: no friction.
class JointFrictionEffect {
 public:
  static constexpr EffectInfo kInfo{
      "joint_friction", Channel::kInternalTorque,
      "the joint's drive resists motion: viscous b·v plus a Coulomb level smoothed over a "
      "small velocity; it shows in the effort only while the joint moves"};

  std::vector<ParameterSpec> Parameters() const;

  template <typename T>
  Vec2<T> operator()(const T* p, const JointState<T>& state) const {
    using std::tanh;
    Vec2<T> out;
    for (int j = 0; j < 2; ++j) {
      const T& v = state.velocity_rad_s[j];
      out[j] = p[j] * v + p[2 + j] * tanh(v / p[4]);
    }
    return out;
  }
};

}  // namespace pliant::models
