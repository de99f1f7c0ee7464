#include "pliant/models/parameters.h"

#include <algorithm>
#include <cmath>
#include <sstream>

namespace pliant::models {
namespace {

std::string ValidateFourier(const BiasTorqueFourier& bias) {
  if (bias.coefficients.empty() || bias.coefficients.size() % 2 == 0) {
    return "bias_torque coefficients must be a0, a1, b1, … (an odd number, at least one)";
  }
  for (double v : bias.coefficients) {
    if (!std::isfinite(v)) return "bias_torque coefficients hold a value that is not finite";
  }
  for (double v : bias.depth_harmonic_nm_per_m) {
    if (!std::isfinite(v)) {
      return "bias_torque depth_harmonic_nm_per_m holds a value that is not finite";
    }
  }
  if (!std::isfinite(bias.depth_slope_nm_per_m) || !(bias.reference_depth_m >= 0.0)) {
    return "bias_torque depth_slope_nm_per_m must be finite and reference_depth_m >= 0";
  }
  return {};
}

// A beam-series law is a sum of compliances in series, each >= 0 by physics;
// then K(L) >= c_joint + c_structure/L > 0 unless both vanish, and the shaft
// term is > 0 wherever L > l_c. That is the whole proof of K > 0 on the range.
std::string ValidateBeamSeries(const JointParameters& joint) {
  const auto& c = joint.compliance.cubic.coefficients;
  for (double v : c) {
    if (!(v >= 0.0) || !std::isfinite(v)) {
      return "compliance beam_series terms must be finite and >= 0 (each is a compliance or a "
             "length)";
    }
  }
  const bool rigid_arm = c[kJointComplianceRadPerNm] == 0.0 && c[kStructureComplianceRadPerN] == 0.0;
  if (rigid_arm && !(c[kShaftFlexibilityPerNm2] > 0.0 && c[kCannulaLengthM] < joint.depth_min_m)) {
    return "the compliance beam_series law is zero somewhere on the valid depth range; it must "
           "stay positive there (give the joint or structure a compliance, or narrow "
           "depth_range_m beyond the cannula)";
  }
  return {};
}

std::string ValidateTable(const BiasTorqueTable& table) {
  std::ostringstream why;
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
  return {};
}

// Physical bounds, so that a typo (1e308) cannot pass as K = 0 or a bias of
// 1e308 N·m. A PSM instrument's K is 0.03–0.1 rad/(N·m) (the paper's eqs. 3–4);
// the band allows a factor of ~300 stiffer and 10 softer. Efforts beyond
// ±10 N·m are beyond what the PSM's joints 1–2 exert (ftmax 3.3 N·m).
constexpr double kComplianceMinRadPerNm = 1e-4;
constexpr double kComplianceMaxRadPerNm = 1.0;
constexpr double kBiasMaxNm = 10.0;

std::string ValidateMagnitudes(const JointParameters& joint) {
  std::ostringstream why;
  for (int i = 0; i <= 30; ++i) {
    const double depth = joint.depth_min_m + (joint.depth_max_m - joint.depth_min_m) * i / 30.0;
    const double k = EvaluateCompliance(joint.compliance.form,
                                        joint.compliance.cubic.coefficients.data(), depth);
    if (!(k >= kComplianceMinRadPerNm && k <= kComplianceMaxRadPerNm)) {
      why << "the compliance law gives K = " << k << " rad/(N·m) at L = " << depth
          << " m; it must lie within [" << kComplianceMinRadPerNm << ", "
          << kComplianceMaxRadPerNm
          << "] rad/(N·m) on the valid depth range (a PSM instrument's is 0.03–0.1)";
      return why.str();
    }
  }
  const std::vector<double>& torques = joint.bias_form == BiasForm::kFourier
                                           ? joint.bias_fourier.coefficients
                                           : joint.bias_torque.torque_nm;
  for (double v : torques) {
    if (!(std::abs(v) <= kBiasMaxNm)) {
      why << "bias_torque holds " << v << " N·m; its values must lie within ±" << kBiasMaxNm
          << " N·m (the PSM's joints 1–2 exert at most 3.3 N·m)";
      return why.str();
    }
  }
  return {};
}

std::string ValidateJoint(const JointParameters& joint) {
  std::ostringstream why;
  const std::string bias = joint.bias_form == BiasForm::kFourier
                               ? ValidateFourier(joint.bias_fourier)
                               : ValidateTable(joint.bias_torque);
  if (!bias.empty()) return bias;
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
  if (joint.compliance.form == ComplianceForm::kBeamSeries) {
    const std::string beam = ValidateBeamSeries(joint);
    return beam.empty() ? ValidateMagnitudes(joint) : beam;
  }
  const double minimum = joint.compliance.cubic.MinimumOn(joint.depth_min_m, joint.depth_max_m);
  if (!(minimum > 0.0)) {
    why << "the compliance cubic reaches " << minimum << " on the valid depth range ["
        << joint.depth_min_m << ", " << joint.depth_max_m
        << "] m; it must stay positive there (narrow depth_range_m or refit)";
    return why.str();
  }
  return ValidateMagnitudes(joint);
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

Eigen::Vector2d CompliancesAt(const std::array<JointParameters, 2>& joints, double depth_m) {
  return {ComplianceAt(joints[0], depth_m), ComplianceAt(joints[1], depth_m)};
}

double BiasTorqueAt(const JointParameters& joint, double angle_rad, double depth_m) {
  if (joint.bias_form == BiasForm::kFourier) {
    const auto& f = joint.bias_fourier;
    return EvaluateFourierBias(f.coefficients.data(), int(f.coefficients.size() / 2),
                               f.depth_slope_nm_per_m, f.depth_harmonic_nm_per_m.data(),
                               f.reference_depth_m, angle_rad, depth_m);
  }
  const auto& t = joint.bias_torque;
  if (t.angle_rad.size() == 1 || angle_rad <= t.angle_rad.front()) return t.torque_nm.front();
  if (angle_rad >= t.angle_rad.back()) return t.torque_nm.back();
  std::size_t i = 1;
  while (angle_rad > t.angle_rad[i]) ++i;
  const double w = (angle_rad - t.angle_rad[i - 1]) / (t.angle_rad[i] - t.angle_rad[i - 1]);
  return t.torque_nm[i - 1] + w * (t.torque_nm[i] - t.torque_nm[i - 1]);
}

void ScaleCompliance(ComplianceLaw& law, double scale) {
  auto& c = law.cubic.coefficients;
  switch (law.form) {
    case ComplianceForm::kInverseCubic:  // 1/K is the cubic
      for (double& x : c) x /= scale;
      break;
    case ComplianceForm::kDirectCubic:
      for (double& x : c) x *= scale;
      break;
    case ComplianceForm::kBeamSeries:
      for (int i : {kJointComplianceRadPerNm, kStructureComplianceRadPerN, kShaftFlexibilityPerNm2})
        c[i] *= scale;
      break;
  }
}

const char* ComplianceFormName(ComplianceForm form) {
  switch (form) {
    case ComplianceForm::kInverseCubic: return "inverse_cubic";
    case ComplianceForm::kDirectCubic: return "direct_cubic";
    case ComplianceForm::kBeamSeries: return "beam_series";
  }
  return "?";
}

bool ComplianceFormNamed(const std::string& name, ComplianceForm* form) {
  for (auto f : {ComplianceForm::kInverseCubic, ComplianceForm::kDirectCubic,
                 ComplianceForm::kBeamSeries}) {
    if (name == ComplianceFormName(f)) {
      *form = f;
      return true;
    }
  }
  return false;
}

}  // namespace pliant::models
