#include "pliant/estimation/compliance_correction.h"

#include <algorithm>
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

// A joint whose bias is a Fourier series gets a flat placeholder table (and
// vice versa), so that both effects can be evaluated for both joints.
models::BiasTorqueTable TableOrFlat(const models::JointParameters& joint) {
  if (joint.bias_form == models::BiasForm::kTable) return joint.bias_torque;
  return {{0.0}, {0.0}};
}

int HarmonicsOf(const models::ModelParameters& p) {
  std::size_t size = 1;
  for (const auto& joint : p.joints) {
    if (joint.bias_form != models::BiasForm::kFourier) continue;
    size = std::max(size, joint.bias_fourier.coefficients.size());
    // Moving a depth harmonic to another reference depth shifts a1 and b1.
    const auto& c = joint.bias_fourier.depth_harmonic_nm_per_m;
    if (c[0] != 0.0 || c[1] != 0.0) size = std::max<std::size_t>(size, 3);
  }
  return int(size / 2);
}

double ReferenceDepthOf(const models::ModelParameters& p) {
  for (const auto& joint : p.joints) {
    if (joint.bias_form == models::BiasForm::kFourier) return joint.bias_fourier.reference_depth_m;
  }
  return 0.155;
}

// Both joints' series padded to the same harmonic count (zeros cost nothing),
// their depth terms moved to one reference depth by shifting a0, a1 and b1.
std::vector<double> FourierValues(const models::ModelParameters& p, int harmonics,
                                  double reference_depth_m) {
  using Effect = models::BiasTorqueFourierEffect;
  std::vector<double> out;
  for (const auto& joint : p.joints) {
    std::vector<double> c(std::size_t(Effect::ParameterCount(harmonics)), 0.0);
    if (joint.bias_form == models::BiasForm::kFourier) {
      const auto& f = joint.bias_fourier;
      std::copy(f.coefficients.begin(), f.coefficients.end(), c.begin());
      const double shift = reference_depth_m - f.reference_depth_m;
      c[std::size_t(Effect::DepthSlopeIndex(harmonics))] = f.depth_slope_nm_per_m;
      c[0] += f.depth_slope_nm_per_m * shift;
      for (int i = 0; i < 2; ++i) {
        c[std::size_t(Effect::DepthHarmonicIndex(harmonics) + i)] = f.depth_harmonic_nm_per_m[i];
        if (harmonics > 0) c[std::size_t(1 + i)] += f.depth_harmonic_nm_per_m[i] * shift;
      }
    }
    out.insert(out.end(), c.begin(), c.end());
  }
  return out;
}

}  // namespace

ComplianceCorrector::ComplianceCorrector(const models::ModelParameters& parameters,
                                         CorrectionModel model)
    : parameters_(Validated(parameters)),
      model_(model),
      bias_(TableOrFlat(parameters.joints[0]), TableOrFlat(parameters.joints[1])),
      bias_fourier_(HarmonicsOf(parameters), ReferenceDepthOf(parameters)),
      compliance_(parameters.joints[0], parameters.joints[1]),
      backlash_sign_(parameters.joints[0].backlash_rad, parameters.joints[1].backlash_rad),
      backlash_deadzone_(parameters.joints[0].backlash_rad, parameters.joints[1].backlash_rad,
                         parameters.joints[0].deadzone_width_nm,
                         parameters.joints[1].deadzone_width_nm),
      extra_(parameters.effects) {
  const auto& j = parameters.joints;
  for (const auto& joint : j) {
    const auto table = TableOrFlat(joint);
    bias_values_.insert(bias_values_.end(), table.torque_nm.begin(), table.torque_nm.end());
  }
  fourier_values_ =
      FourierValues(parameters, HarmonicsOf(parameters), ReferenceDepthOf(parameters));
  for (const auto& joint : j) {
    for (double c : joint.compliance.cubic.coefficients) compliance_values_.push_back(c);
  }
  sign_values_ = {j[0].backlash_rad, j[1].backlash_rad};
  deadzone_values_ = {j[0].backlash_rad, j[1].backlash_rad, j[0].deadzone_width_nm,
                      j[1].deadzone_width_nm};
}

JointCorrection ComplianceCorrector::Correct(const Eigen::Vector3d& q,
                                             const Eigen::Vector2d& measured_torque_nm,
                                             const Eigen::Vector2d& travel_since_reversal_rad) const {
  models::JointState<double> state;
  state.encoder_angle_rad = q.head<2>();
  state.insertion_depth_m = q[2];
  state.travel_since_reversal_rad = travel_since_reversal_rad;
  return Correct(state, measured_torque_nm);
}

JointCorrection ComplianceCorrector::Correct(const models::JointState<double>& inputs,
                                             const Eigen::Vector2d& measured_torque_nm) const {
  models::JointState<double> state = inputs;
  const Eigen::Vector3d q(state.encoder_angle_rad[0], state.encoder_angle_rad[1],
                          state.insertion_depth_m);
  const Eigen::Vector2d internal = extra_.InternalTorque(state);
  const Eigen::Vector2d table = bias_(bias_values_.data(), state);
  const Eigen::Vector2d fourier = bias_fourier_(fourier_values_.data(), state);
  for (int j = 0; j < 2; ++j) {
    const bool smooth = parameters_.joints[j].bias_form == models::BiasForm::kFourier;
    state.external_torque_nm[j] =
        measured_torque_nm[j] - (smooth ? fourier[j] : table[j]) - internal[j];
  }

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
  if (!extra_.empty()) {
    state.compliance_rad_per_nm = models::CompliancesAt(parameters_.joints, q[2]);
    out.deflection_rad += extra_.Deflection(state);
  }
  out.corrected_rad = q.head<2>() - out.deflection_rad;
  // A joint the row does not read (no encoder angle: a log of the other
  // joint) has no depth range to leave.
  for (int j = 0; j < 2; ++j) {
    const auto& joint = parameters_.joints[j];
    out.depth_clamped |= std::isfinite(q[j]) && (q[2] < joint.depth_min_m || q[2] > joint.depth_max_m);
  }
  return out;
}

double ComplianceCorrector::JumpAtThreshold(int joint, double depth_m) const {
  if (model_ == CorrectionModel::kDeadZone) return 0.0;
  const auto& p = parameters_.joints.at(joint);
  return p.backlash_rad + models::ComplianceAt(p, depth_m) * p.tau_min_nm;
}

}  // namespace pliant::estimation
