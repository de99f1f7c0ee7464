#pragma once
// Load-dependent compliance: the shaft's bend is not exactly linear in the
// load (the tube ovalises, the contact with the cannula moves along the
// shaft). The paper's K(L) is a constant at each depth.

#include <string>
#include <vector>

#include "pliant/models/effect.h"

namespace pliant::models {

/// Extra deflection gamma_j·tau_ext_j³ (rad): the incremental compliance
/// becomes K(L) + 3·gamma_j·tau_ext_j², softer under load when gamma > 0 and
/// stiffer when gamma < 0. Smooth (a cubic), odd in the load.
/// Parameters: gamma1, gamma2 (rad/(N·m)³). Defaults: linear shaft.
class LoadDependentComplianceEffect {
 public:
  static constexpr EffectInfo kInfo{
      "load_dependent_compliance", Channel::kDeflection,
      "the shaft bends more (gamma > 0) or less per N·m as the load grows: extra gamma·tau³"};

  std::vector<ParameterSpec> Parameters() const;

  template <typename T>
  Vec2<T> operator()(const T* gamma, const JointState<T>& state) const {
    const Vec2<T>& tau = state.external_torque_nm;
    return {gamma[0] * tau[0] * tau[0] * tau[0], gamma[1] * tau[1] * tau[1] * tau[1]};
  }
};

}  // namespace pliant::models
