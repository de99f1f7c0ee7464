#pragma once
// Load-dependent compliance: the shaft's bend is not exactly linear in the
// load (the tube ovalises, the contact with the cannula moves along the
// shaft). The paper's K(L) is a constant at each depth.

#include <string>
#include <vector>

#include "pliant/models/effect.h"

namespace pliant::models {

/// Extra deflection beta_j·tau_j·|tau_j| + gamma_j·tau_j³ (rad), the first two
/// odd terms of a compliance that depends on the load's size: the incremental
/// compliance becomes K(L) + 2·beta_j·|tau_j| + 3·gamma_j·tau_j². beta is the
/// leading term of any stiffness that grows with the load's magnitude (a
/// contact pressed harder, K/(1 + a·|tau|) ≈ K − a·K·|tau|), which bends the
/// curve already at small loads; gamma (the tube ovalising) bends it at large
/// ones. Softer under load when positive, stiffer when negative. Odd in the
/// load, continuous in slope at zero. Parameters: gamma1, gamma2
/// (rad/(N·m)³), beta1, beta2 (rad/(N·m)²). Defaults: linear shaft.
class LoadDependentComplianceEffect {
 public:
  static constexpr EffectInfo kInfo{
      "load_dependent_compliance", Channel::kDeflection,
      "the shaft bends more (> 0) or less (< 0) per N·m as the load grows: extra "
      "beta·tau·|tau| + gamma·tau³"};

  std::vector<ParameterSpec> Parameters() const;

  template <typename T>
  Vec2<T> operator()(const T* p, const JointState<T>& state) const {
    using std::abs;
    const Vec2<T>& tau = state.external_torque_nm;
    return {p[2] * tau[0] * abs(tau[0]) + p[0] * tau[0] * tau[0] * tau[0],
            p[3] * tau[1] * abs(tau[1]) + p[1] * tau[1] * tau[1] * tau[1]};
  }
};

}  // namespace pliant::models
