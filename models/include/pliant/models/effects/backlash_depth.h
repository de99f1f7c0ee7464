#pragma once
// Depth-dependent backlash: the clearance the shaft crosses inside the cannula
// is not one angle. Seen from the remote centre of motion a lateral play c of
// the shaft at the cannula's seal is an angle c/L that changes with the
// insertion depth L, and a worn seal adds play of its own. The paper's delta_j
// is a constant.

#include <string>
#include <vector>

#include "pliant/models/effect.h"
#include "pliant/models/smooth.h"

namespace pliant::models {

/// Extra deflection (d0_j + d1_j·(L − L_ref))·S(tau_ext_j / w_j) (rad): more
/// (or less) clearance than the model's delta_j, growing linearly with depth
/// about L_ref = 0.155 m (the middle of the paper's depth range), taken up as
/// the load builds over w_j like the base model's dead zone.
/// Parameters: clearance1, clearance2 (rad), growth1, growth2 (rad/m),
/// width1, width2 (N·m). Defaults: no extra clearance.
class BacklashDepthEffect {
 public:
  static constexpr EffectInfo kInfo{
      "backlash_depth", Channel::kDeflection,
      "the cannula clearance seen at the joint changes with insertion depth: extra backlash "
      "(d0 + d1·(L − 0.155 m))·S(tau/w) on top of the model's constant delta"};
  static constexpr double kReferenceDepthM = 0.155;

  std::vector<ParameterSpec> Parameters() const;

  template <typename T>
  Vec2<T> operator()(const T* p, const JointState<T>& state) const {
    const T lever = state.insertion_depth_m - kReferenceDepthM;
    Vec2<T> out;
    for (int j = 0; j < 2; ++j) {
      out[j] = (p[j] + p[2 + j] * lever) * SmoothSaturation(state.external_torque_nm[j] / p[4 + j]);
    }
    return out;
  }
};

}  // namespace pliant::models
