#pragma once
// A user's own effect (docs/tutorial-missing-effect.md): the shaft is softer
// when pushed one way than the other — the paper's Fig. 6 finds K(L) not
// symmetric — so a positive load bends it by an extra c_j per N·m.
#include <vector>

#include <pliant/models/effect.h>

struct OneSidedCompliance {
  static constexpr pliant::models::EffectInfo kInfo{
      "one_sided_compliance", pliant::models::Channel::kDeflection,
      "the shaft bends an extra c per N·m under a positive load only (asymmetric bending)"};

  std::vector<pliant::models::ParameterSpec> Parameters() const {
    // name, unit, default (off), lower and upper bound, prior σ
    return {{"c1", "rad/(N·m)", 0.0, -0.05, 0.05, 0.01},
            {"c2", "rad/(N·m)", 0.0, -0.05, 0.05, 0.01}};
  }

  template <typename T>
  pliant::models::Vec2<T> operator()(const T* c,
                                     const pliant::models::JointState<T>& state) const {
    pliant::models::Vec2<T> bend;
    for (int j = 0; j < 2; ++j) {
      const T& load = state.external_torque_nm[j];
      bend[j] = load > 0.0 ? c[j] * load : T(0.0);
    }
    return bend;
  }
};
