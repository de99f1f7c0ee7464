#pragma once
// Held friction: the drive's Coulomb friction stays loaded when the joint
// stops. A position-controlled joint that has moved in one direction and
// stopped holds, in its measured effort, the friction of that last motion:
// +F when it last moved toward +q, −F toward −q. On reversal the friction
// does not flip at once: it passes through zero over a short presliding
// travel λ (Dahl's friction model, integrated over a monotone travel d):
//
//   tau_j = F_j · z(d_j),   z(d) = sgn(d) · (1 − 2·exp(−|d| / λ))
//
// d_j is the signed encoder travel since the joint last reversed
// (JointState::travel_since_reversal_rad, from models::TravelSinceReversal);
// z = −1 just after a reversal (the previous motion's friction) and tends to
// +1 (this motion's) after a few λ. d = 0 (never moved) gives z = 0.
//
// The real clamped-beam data of the paper (docs/real-data.md) show it: the
// loading and unloading branches are parallel lines offset by the same
// ≈ 0.2 N·m of effort at every depth, i.e. by 2·K(L)·F in angle. The paper's
// model reads that offset as cannula clearance δ.

#include <cmath>
#include <string>
#include <vector>

#include "pliant/models/effect.h"

namespace pliant::models {

/// Parameters: held_friction1, held_friction2 (N·m), presliding_travel (rad).
/// Defaults: no friction, λ = 2 mrad (the real clamped beam's best fit).
class HeldFrictionEffect {
 public:
  static constexpr EffectInfo kInfo{
      "held_friction", Channel::kInternalTorque,
      "the drive's Coulomb friction stays in the effort when the joint stops: +F after moving "
      "toward +q, -F toward -q, passing through zero over a short travel after each reversal"};

  std::vector<ParameterSpec> Parameters() const {
    return {{"held_friction1", "N·m", 0.0, 0.0, 1.0, 0.1},
            {"held_friction2", "N·m", 0.0, 0.0, 1.0, 0.1},
            {"presliding_travel", "rad", 0.002, 1e-4, 0.05, 0.002}};
  }

  template <typename T>
  Vec2<T> operator()(const T* p, const JointState<T>& state) const {
    using std::abs;
    using std::exp;
    Vec2<T> out;
    for (int j = 0; j < 2; ++j) {
      const T& d = state.travel_since_reversal_rad[j];
      if (d == 0.0) {
        out[j] = T(0.0);
        continue;
      }
      const T z = T(1.0) - T(2.0) * exp(-abs(d) / p[2]);
      out[j] = d > 0.0 ? p[j] * z : -p[j] * z;
    }
    return out;
  }
};

}  // namespace pliant::models
