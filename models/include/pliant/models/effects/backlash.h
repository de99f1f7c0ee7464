#pragma once
// Backlash: the shaft shifts inside the cannula clearance before it bears on
// the cannula wall (paper, Fig. 2 right). Two shapes of the same effect.

#include <cmath>
#include <string>
#include <vector>

#include "pliant/models/effect.h"
#include "pliant/models/smooth.h"

namespace pliant::models {

/// The paper's backlash, delta_j·sgn(tau_ext_j) (rad): the shaft sits at one
/// wall or the other, and jumps between them when the torque changes sign.
/// Parameters: delta1, delta2 (rad).
class BacklashSignEffect {
 public:
  static constexpr EffectInfo kInfo{
      "backlash_sign", Channel::kDeflection,
      "the shaft sits against one cannula wall or the other, by the sign of the load"};

  explicit BacklashSignEffect(double delta1_rad = 0.008478, double delta2_rad = 0.007176);

  std::vector<ParameterSpec> Parameters() const;

  template <typename T>
  Vec2<T> operator()(const T* delta_rad, const JointState<T>& state) const {
    Vec2<T> out;
    for (int j = 0; j < 2; ++j) {
      const T& tau = state.external_torque_nm[j];
      out[j] = tau > 0.0 ? delta_rad[j] : (tau < 0.0 ? -delta_rad[j] : T(0.0));
    }
    return out;
  }

 private:
  double delta_rad_[2];
};

/// Continuous dead-zone backlash, delta_j·S(tau_ext_j / w_j) (rad), where S is
/// the smooth saturation of smooth.h: the shaft crosses the clearance as the
/// load builds from 0 to w_j and rests on the wall, at exactly ±delta_j, beyond.
/// Unlike the paper's sgn and tau_min switch it has no jump.
/// Parameters: delta1, delta2 (rad), width1, width2 (N·m).
class BacklashDeadZoneEffect {
 public:
  static constexpr EffectInfo kInfo{
      "backlash_deadzone", Channel::kDeflection,
      "the shaft crosses the cannula clearance as the load builds, then rests on the wall"};

  explicit BacklashDeadZoneEffect(double delta1_rad = 0.008478, double delta2_rad = 0.007176,
                                  double width1_nm = 0.1, double width2_nm = 0.2);

  std::vector<ParameterSpec> Parameters() const;

  template <typename T>
  Vec2<T> operator()(const T* p, const JointState<T>& state) const {
    return {p[0] * SmoothSaturation(state.external_torque_nm[0] / p[2]),
            p[1] * SmoothSaturation(state.external_torque_nm[1] / p[3])};
  }

 private:
  double defaults_[4];
};

}  // namespace pliant::models
