#pragma once
// Load-dependent compliance: the shaft's bend is not exactly linear in the
// load (the tube ovalises, the contact with the cannula moves along the
// shaft). The paper's K(L) is a constant at each depth.

#include <string>
#include <vector>

#include "pliant/models/effect.h"

namespace pliant::models {

/// Extra deflection K_j(L)·(beta_j·tau_j·|tau_j| + gamma_j·tau_j³) (rad), the
/// first two odd terms of a compliance that depends on the load's size, as a
/// share of the shaft's own K(L) at this depth (JointState::
/// compliance_rad_per_nm): the incremental compliance becomes
/// K(L)·(1 + 2·beta_j·|tau_j| + 3·gamma_j·tau_j²). A stiffness that grows with
/// the load's magnitude — a contact pressed harder, K/(1 + a·|tau|) ≈
/// K·(1 − a·|tau| + a²·tau²) — is beta = −a, gamma = a² at every depth; an
/// absolute beta would have to change with K(L) from depth to depth. beta
/// bends the curve already at small loads, gamma (the tube ovalising) at large
/// ones. Softer under load when positive, stiffer when negative. Odd in the
/// load, continuous in slope at zero. Parameters: gamma1, gamma2 (1/(N·m)²),
/// beta1, beta2 (1/(N·m)). Defaults: linear shaft.
class LoadDependentComplianceEffect {
 public:
  static constexpr EffectInfo kInfo{
      "load_dependent_compliance", Channel::kDeflection,
      "the shaft bends more (> 0) or less (< 0) per N·m as the load grows: extra "
      "K(L)·(beta·tau·|tau| + gamma·tau³)"};

  std::vector<ParameterSpec> Parameters() const;

  template <typename T>
  Vec2<T> operator()(const T* p, const JointState<T>& state) const {
    using std::abs;
    const Vec2<T>& tau = state.external_torque_nm;
    const Vec2<T>& k = state.compliance_rad_per_nm;
    return {k[0] * (p[2] * tau[0] * abs(tau[0]) + p[0] * tau[0] * tau[0] * tau[0]),
            k[1] * (p[3] * tau[1] * abs(tau[1]) + p[1] * tau[1] * tau[1] * tau[1])};
  }
};

}  // namespace pliant::models
