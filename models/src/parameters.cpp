#include "pliant/models/parameters.h"

#include <algorithm>
#include <cmath>
#include <sstream>

namespace pliant::models {
namespace {

std::string ValidateJoint(const JointParameters& joint) {
  std::ostringstream why;
  const auto& table = joint.bias_torque;
  if (table.angle_rad.empty() || table.angle_rad.size() != table.torque_nm.size()) {
    why << "bias_torque needs as many angle_rad as torque_nm values, at least one";
    return why.str();
  }
  for (std::size_t i = 1; i < table.angle_rad.size(); ++i) {
    if (!(table.angle_rad[i] > table.angle_rad[i - 1])) {
      why << "bias_torque angle_rad must be strictly increasing (entry " << i << ")";
      return why.str();
    }
  }
  for (double v : table.torque_nm) {
    if (!std::isfinite(v)) return "bias_torque torque_nm holds a value that is not finite";
  }
  if (!(joint.depth_min_m > 0.0 && joint.depth_max_m > joint.depth_min_m &&
        joint.depth_max_m <= 0.3)) {
    return "depth_range_m must be [min, max] with 0 < min < max <= 0.3 m";
  }
  if (!(joint.backlash_rad >= 0.0 && joint.backlash_rad < 0.1)) {
    return "backlash_rad must be in [0, 0.1) rad";
  }
  if (!(joint.tau_min_nm >= 0.0 && joint.tau_min_nm < 10.0)) {
    return "tau_min_nm must be in [0, 10) N·m";
  }
  if (!(joint.deadzone_width_nm > 0.0 && joint.deadzone_width_nm < 10.0)) {
    return "deadzone_width_nm must be in (0, 10) N·m";
  }
  const double minimum = joint.compliance.cubic.MinimumOn(joint.depth_min_m, joint.depth_max_m);
  if (!(minimum > 0.0)) {
    why << "the compliance cubic reaches " << minimum << " on the valid depth range ["
        << joint.depth_min_m << ", " << joint.depth_max_m
        << "] m; it must stay positive there (narrow depth_range_m or refit)";
    return why.str();
  }
  return {};
}

}  // namespace

std::string ValidateParameters(const ModelParameters& parameters) {
  for (int j = 0; j < 2; ++j) {
    const std::string why = ValidateJoint(parameters.joints[j]);
    if (!why.empty()) return "joint" + std::to_string(j + 1) + ": " + why;
  }
  if (parameters.covariance) {
    const auto& c = *parameters.covariance;
    const auto n = static_cast<Eigen::Index>(c.names.size());
    if (c.matrix.rows() != n || c.matrix.cols() != n) {
      return "covariance matrix must be square with one row per name";
    }
    if (!c.matrix.isApprox(c.matrix.transpose(), 1e-9)) return "covariance must be symmetric";
  }
  return {};
}

double ComplianceAt(const JointParameters& joint, double depth_m) {
  const double depth = std::clamp(depth_m, joint.depth_min_m, joint.depth_max_m);
  return EvaluateCompliance(joint.compliance.form, joint.compliance.cubic.coefficients.data(),
                            depth);
}

}  // namespace pliant::models
