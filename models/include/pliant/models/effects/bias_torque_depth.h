#pragma once
// Depth-dependent bias torque: as the instrument is inserted its weight moves
// along the shaft, so the torque the controller spends holding a joint still
// changes with the insertion depth. The paper's tau0(q) is a function of the
// joint angle only (its Fig. 4 shows little depth dependence); the dVRK's 2017
// parameter file made joint 2's bias linear in q3 (−0.2419 N·m/m).

#include <string>
#include <vector>

#include "pliant/models/effect.h"

namespace pliant::models {

/// tau_j = s_j·(L − L_ref) (N·m), L the insertion depth.
/// Parameters: slope1, slope2 (N·m/m), reference_depth (m). Defaults: flat.
class BiasTorqueDepthEffect {
 public:
  static constexpr EffectInfo kInfo{
      "bias_torque_depth", Channel::kInternalTorque,
      "the instrument's weight moves along the shaft as it is inserted, so the bias changes "
      "linearly with depth"};

  std::vector<ParameterSpec> Parameters() const;

  template <typename T>
  Vec2<T> operator()(const T* p, const JointState<T>& state) const {
    const T lever = state.insertion_depth_m - p[2];
    return {p[0] * lever, p[1] * lever};
  }
};

}  // namespace pliant::models
