#pragma once
// The joint smoother's parameters the logs leave at their prior
// (identification_common.h, UndeterminedParameters): which of its global
// numbers they are, and what their prior uncertainty does to K and delta, in
// words (consider_covariance.h has the statistics).

#include <string>
#include <vector>

#include <Eigen/Core>

#include "identification_common.h"
#include "joint_smoother_setup.h"

namespace pliant::estimation::detail {

/// Indices of the held parameters in the smoother's global vector (law1, law2,
/// delta1, delta2, log w1, log w2, bias1, bias2; joint_smoother.cpp) and their
/// prior sd. A bias depth slope the options hold at 0 is not among them.
void HeldParameters(const UndeterminedParameters& held, const SmootherPrior& prior,
                    const JointSmootherOptions& options, std::vector<long>* indices,
                    std::vector<double>* prior_sd);

/// One sentence per joint that holds something at its prior: K at the middle
/// of the loaded depths (and delta when estimated) with the sd the file
/// carries and the sd of the fit alone (`conditional`, the smoother's global
/// order with log w), so that the user sees how much the missing experiment costs.
std::vector<std::string> HeldParameterWarnings(const models::ModelParameters& fitted,
                                               const Eigen::MatrixXd& conditional,
                                               const UndeterminedParameters& held);

}  // namespace pliant::estimation::detail
