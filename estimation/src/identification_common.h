#pragma once
// Small pieces shared by the paper's procedure and the joint smoother.

#include <string>
#include <vector>

#include <Eigen/Core>

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

}  // namespace pliant::estimation::detail
