#include "pliant/estimation/compliance_correction.h"

#include <cmath>
#include <stdexcept>

namespace pliant::estimation {

std::optional<CorrectionModel> ParseCorrectionModel(std::string_view name) {
  if (name == "paper") return CorrectionModel::kPaper;
  if (name == "deadzone") return CorrectionModel::kDeadZone;
  return std::nullopt;
}

namespace {

const models::ModelParameters& Validated(const models::ModelParameters& parameters) {
  const std::string why = models::ValidateParameters(parameters);
  if (!why.empty()) throw std::invalid_argument(why);
  return parameters;
}

std::vector<double> Concatenate(const std::vector<double>& a, const std::vector<double>& b) {
  std::vector<double> out = a;
  out.insert(out.end(), b.begin(), b.end());
  return out;
}

}  // namespace

ComplianceCorrector::ComplianceCorrector(const models::ModelParameters& parameters,
                                         CorrectionModel model)
    : parameters_(Validated(parameters)),
      model_(model),
      bias_(parameters.joints[0].bias_torque, parameters.joints[1].bias_torque),
      compliance_(parameters.joints[0], parameters.joints[1]),
      backlash_sign_(parameters.joints[0].backlash_rad, parameters.joints[1].backlash_rad),
      backlash_deadzone_(parameters.joints[0].backlash_rad, parameters.joints[1].backlash_rad,
                         parameters.joints[0].deadzone_width_nm,
                         parameters.joints[1].deadzone_width_nm) {
  const auto& j = parameters.joints;
  bias_values_ = Concatenate(j[0].bias_torque.torque_nm, j[1].bias_torque.torque_nm);
  for (const auto& joint : j) {
    for (double c : joint.compliance.cubic.coefficients) compliance_values_.push_back(c);
  }
  sign_values_ = {j[0].backlash_rad, j[1].backlash_rad};
  deadzone_values_ = {j[0].backlash_rad, j[1].backlash_rad, j[0].deadzone_width_nm,
                      j[1].deadzone_width_nm};
}

JointCorrection ComplianceCorrector::Correct(const Eigen::Vector3d& q,
                                             const Eigen::Vector2d& measured_torque_nm) const {
  models::JointState<double> state;
  state.encoder_angle_rad = q.head<2>();
  state.insertion_depth_m = q[2];
  state.external_torque_nm =
      measured_torque_nm - bias_(bias_values_.data(), state);

  JointCorrection out;
  out.external_torque_nm = state.external_torque_nm;
  const Eigen::Vector2d bend = compliance_(compliance_values_.data(), state);
  if (model_ == CorrectionModel::kPaper) {
    const Eigen::Vector2d shift = backlash_sign_(sign_values_.data(), state);
    for (int j = 0; j < 2; ++j) {
      const bool loaded = std::abs(state.external_torque_nm[j]) > parameters_.joints[j].tau_min_nm;
      out.deflection_rad[j] = loaded ? shift[j] + bend[j] : 0.0;
    }
  } else {
    out.deflection_rad = backlash_deadzone_(deadzone_values_.data(), state) + bend;
  }
  out.corrected_rad = q.head<2>() - out.deflection_rad;
  for (const auto& joint : parameters_.joints) {
    out.depth_clamped |= q[2] < joint.depth_min_m || q[2] > joint.depth_max_m;
  }
  return out;
}

double ComplianceCorrector::JumpAtThreshold(int joint, double depth_m) const {
  if (model_ == CorrectionModel::kDeadZone) return 0.0;
  const auto& p = parameters_.joints.at(joint);
  return p.backlash_rad + models::ComplianceAt(p, depth_m) * p.tau_min_nm;
}

}  // namespace pliant::estimation
