#pragma once
// Checks an effect's automatic derivatives against central differences, with
// respect to every parameter and every input of the joint state. Run it on
// your own effect before you rely on it in the filter or the smoother:
//
//   auto result = pliant::estimation::CheckEffectJacobians(
//       pliant::estimation::MakeEffectModel(CrossCoupling{}), {0.01}, state);
//   EXPECT_TRUE(result.ok) << result.Report();
//
// Choose the state away from kinks the effect has on purpose (sgn at zero
// load, table knots, the ends of a clamp): there no derivative exists.

#include <memory>
#include <string>
#include <vector>

#include <Eigen/Core>

#include "pliant/estimation/effect_catalogue.h"

namespace pliant::estimation {

struct JacobianCheckOptions {
  /// Central-difference step relative to max(1, |x|).
  double relative_step = 1e-6;
  /// Largest accepted |autodiff − numeric| / max(1, |numeric|).
  double tolerance = 1e-5;
};

struct JacobianCheckResult {
  bool ok = false;
  /// 2 × (parameters + kJointStateSize): d(contribution of joint j)/d(input).
  Eigen::MatrixXd autodiff;
  Eigen::MatrixXd numeric;
  double worst_error = 0.0;
  std::string worst_entry;  ///< e.g. "d joint1 / d delta1"

  /// A readable table of the entries that disagree, or a one-line "ok".
  std::string Report() const;
};

/// Names of the state inputs, in the order of the Jacobian's last columns.
const std::vector<std::string>& JointStateInputNames();

JacobianCheckResult CheckEffectJacobians(const EffectModel& effect,
                                         const std::vector<double>& parameters,
                                         const models::JointState<double>& state,
                                         const JacobianCheckOptions& options = {});

inline JacobianCheckResult CheckEffectJacobians(const std::unique_ptr<EffectModel>& effect,
                                                const std::vector<double>& parameters,
                                                const models::JointState<double>& state,
                                                const JacobianCheckOptions& options = {}) {
  return CheckEffectJacobians(*effect, parameters, state, options);
}

}  // namespace pliant::estimation
