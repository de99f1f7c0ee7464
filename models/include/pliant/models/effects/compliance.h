#pragma once
// Compliance K(L): the instrument shaft bends under a lateral load, and the
// bend grows with the lever arm L from the remote centre of motion (paper,
// equation 1 and Fig. 6). Encoders do not see it.

#include <algorithm>
#include <string>
#include <vector>

#include "pliant/models/effect.h"
#include "pliant/models/parameters.h"

namespace pliant::models {

/// Deflection K_j(L)·tau_ext_j (rad) per joint. Parameters: the four cubic
/// coefficients of each joint (joint 1's first), in the joint's form (the
/// paper's 1/K cubic or the dVRK file's direct K cubic). The depth is clamped to
/// each joint's valid range, where ValidateParameters has proved K finite and
/// positive.
class ComplianceEffect {
 public:
  static constexpr EffectInfo kInfo{
      "compliance", Channel::kDeflection,
      "the shaft bends under lateral load, more the deeper it is inserted"};

  /// The paper's equations (3) and (4) on 0.09–0.22 m.
  ComplianceEffect();
  ComplianceEffect(const JointParameters& joint1, const JointParameters& joint2);

  std::vector<ParameterSpec> Parameters() const;

  template <typename T>
  Vec2<T> operator()(const T* coefficients, const JointState<T>& state) const {
    Vec2<T> deflection;
    for (int j = 0; j < 2; ++j) {
      T depth = state.insertion_depth_m;
      if (depth < depth_min_m_[j]) depth = T(depth_min_m_[j]);
      if (depth > depth_max_m_[j]) depth = T(depth_max_m_[j]);
      const T k = EvaluateCompliance(forms_[j], coefficients + 4 * j, depth);
      deflection[j] = k * state.external_torque_nm[j];
    }
    return deflection;
  }

 private:
  ComplianceForm forms_[2];
  double depth_min_m_[2];
  double depth_max_m_[2];
  std::vector<double> defaults_;
};

}  // namespace pliant::models
