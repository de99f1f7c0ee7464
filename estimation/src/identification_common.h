#pragma once
// Small pieces shared by the paper's procedure and the joint smoother.

#include <array>
#include <set>
#include <string>
#include <vector>

#include <Eigen/Core>

#include "pliant/estimation/identification.h"
#include "pliant/models/parameters.h"

namespace pliant::estimation::detail {

/// Covariance names of a joint's four law numbers (docs/parameters.md).
std::vector<std::string> LawNames(int joint, models::ComplianceForm form);

/// Condition number of the correlation matrix of a covariance (scale-free:
/// a large value means two parameters the data can hardly tell apart).
double CorrelationCondition(const Eigen::MatrixXd& covariance);

/// Seconds since `start` (steady clock, in seconds).
double SecondsSince(double start);
double NowSeconds();

/// Parameters the logs leave at their prior, per joint: the bias tau0 when no
/// free-tip row measures it (a held tip cannot tell its slope from 1/K, nor
/// its level from the tip angle), and delta when the tip is held but no
/// tip_fixed segment loads the joint both ways. The smoother holds them at the prior mean and carries
/// the prior's covariance into the others' (consider_covariance.h). `depth_harmonic`
/// (per joint, the bias's c1 and d1, set by HoldUndeterminedDepthHarmonic) is
/// held at its prior mean without that, as a depth slope held by
/// bias_depth_term = false is.
struct UndeterminedParameters {
  std::array<bool, 2> bias{{false, false}}, backlash{{false, false}};
  std::array<std::array<bool, 2>, 2> depth_harmonic{};
};
/// The tip_fixed segments that load joint j: those whose joint-j effort spans
/// at least a fifth of the widest clamp's span. A log that records both joints
/// in every clamp holds, for each joint, clamps pushed along the other joint:
/// their rows sit at one unknown load inside the joint's clearance and
/// friction band, so they say nothing of K and pull the fit's clearance and
/// friction to explain a load that is not there.
std::set<int> ClampsThatLoad(const IdentificationData& data, int j);

UndeterminedParameters FindUndetermined(const IdentificationData& data,
                                        const models::ModelParameters& bias,
                                        const PaperProcedureOptions& options);

}  // namespace pliant::estimation::detail
