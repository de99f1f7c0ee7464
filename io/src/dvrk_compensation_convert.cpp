// Between the dVRK's compensation model and pliant's parameters (dvrk_compensation.h).
#include <algorithm>
#include <cmath>
#include <cstdio>

#include <Eigen/Dense>

#include "pliant/io/dvrk_compensation.h"
#include "pliant/io/input_error.h"

namespace pliant::io {
namespace {

// The paper's values for what the dVRK file does not hold (data/paper.json).
constexpr double kPaperTauMinNm[2] = {0.1, 0.2};
constexpr double kPaperDepthMinM = 0.09;
constexpr double kPaperDepthMaxM = 0.22;
// The PSM's joint ranges (dVRK configuration files), over which an angle term is measured.
constexpr double kJointRangeRad[2] = {1.588, 0.925};

std::string Format(const char* format, double a, double b = 0.0, double c = 0.0) {
  char text[256];
  std::snprintf(text, sizeof text, format, a, b, c);
  return text;
}

// K(L) as a cubic in L, least squares at 61 depths over the valid range;
// `worst` receives the largest relative difference from the law.
std::array<double, 4> FitDirectCubic(const models::JointParameters& joint, double* worst) {
  constexpr int kDepths = 61;
  Eigen::MatrixXd powers(kDepths, 4);
  Eigen::VectorXd compliance(kDepths);
  for (int i = 0; i < kDepths; ++i) {
    const double depth =
        joint.depth_min_m + (joint.depth_max_m - joint.depth_min_m) * i / (kDepths - 1);
    powers.row(i) << depth * depth * depth, depth * depth, depth, 1.0;
    compliance(i) = models::ComplianceAt(joint, depth);
  }
  const Eigen::Vector4d c = powers.colPivHouseholderQr().solve(compliance);
  *worst = ((powers * c - compliance).array() / compliance.array()).abs().maxCoeff();
  return {c(0), c(1), c(2), c(3)};
}

// The bias torque's largest departure over the joint's range from its value at q = 0.
double AngleVariation(const models::JointParameters& joint, int index, double depth_m) {
  double largest = 0.0;
  const double at_zero = models::BiasTorqueAt(joint, 0.0, depth_m);
  for (int i = -50; i <= 50; ++i) {
    const double angle = kJointRangeRad[index] * i / 50.0;
    largest = std::max(largest, std::abs(models::BiasTorqueAt(joint, angle, depth_m) - at_zero));
  }
  return largest;
}

}  // namespace

models::ModelParameters DvrkToParameters(const DvrkCompensation& compensation,
                                         const std::string& file) {
  models::ModelParameters parameters;
  parameters.description = "Read from the dVRK compensation file " + file +
                           " (mtsPSMCompensation); tau_min and the depth range are the paper's.";
  for (int j = 0; j < 2; ++j) {
    models::JointParameters& joint = parameters.joints[j];
    const auto& offset = compensation.torque_offset[j];
    joint.bias_form = models::BiasForm::kFourier;
    joint.bias_fourier.coefficients = {j == 0 ? offset[0] : offset[1]};
    joint.bias_fourier.depth_slope_nm_per_m = j == 0 ? 0.0 : offset[0];
    joint.bias_fourier.reference_depth_m = 0.0;
    joint.compliance.form = models::ComplianceForm::kDirectCubic;
    std::copy(compensation.compliance[j].begin(), compensation.compliance[j].end(),
              joint.compliance.cubic.coefficients.begin());
    joint.backlash_rad = compensation.backlash_rad[j];
    joint.tau_min_nm = joint.deadzone_width_nm = kPaperTauMinNm[j];
    joint.depth_min_m = kPaperDepthMinM;
    joint.depth_max_m = kPaperDepthMaxM;
    const std::string which = j == 0 ? "_first" : "_second";
    joint.sources["compliance"] = file + ": compliance" + which;
    joint.sources["bias_torque"] = file + ": torque_offset" + which +
                                   (j == 0 ? " (tau0 = value-a)" : " (tau0 = value-a·q3 + value-b)");
    joint.sources["backlash_rad"] = file + ": backlash" + which;
    joint.sources["tau_min_nm"] = "the paper (the dVRK file holds none)";
    joint.sources["depth_range_m"] = "the paper's 14 depths (the dVRK file holds none)";
  }
  const std::string why = models::ValidateParameters(parameters);
  if (!why.empty()) {
    throw InputError(file, 0, 0, "the dVRK compensation file's values are not usable: " + why,
                     "correct the value in the file (docs/parameters.md, 'The dVRK's "
                     "compensation file')");
  }
  return parameters;
}

DvrkCompensation ParametersToDvrk(const models::ModelParameters& parameters,
                                  std::vector<std::string>* notes) {
  DvrkCompensation out;
  for (int j = 0; j < 2; ++j) {
    const models::JointParameters& joint = parameters.joints[j];
    const std::string name = "joint " + std::to_string(j + 1) + ": ";
    if (joint.compliance.form == models::ComplianceForm::kDirectCubic) {
      std::copy(joint.compliance.cubic.coefficients.begin(),
                joint.compliance.cubic.coefficients.end(), out.compliance[j].begin());
    } else {
      double worst = 0.0;
      out.compliance[j] = FitDirectCubic(joint, &worst);
      notes->push_back(name + models::ComplianceFormName(joint.compliance.form) +
                       Format(" K(L) written as a cubic fitted over %.3f–%.3f m (largest "
                              "difference %.2g %% of K)",
                              joint.depth_min_m, joint.depth_max_m, 100.0 * worst));
    }
    out.backlash_rad[j] = joint.backlash_rad;
    const auto& fourier = joint.bias_fourier;
    const bool depth_linear =
        joint.bias_form == models::BiasForm::kFourier && fourier.coefficients.size() == 1 &&
        fourier.reference_depth_m == 0.0 && fourier.depth_harmonic_nm_per_m[0] == 0.0 &&
        fourier.depth_harmonic_nm_per_m[1] == 0.0;
    const double middle = 0.5 * (joint.depth_min_m + joint.depth_max_m);
    if (depth_linear && (j == 1 || fourier.depth_slope_nm_per_m == 0.0)) {
      // The component's own form: copied, so that dVRK -> pliant -> dVRK is exact.
      out.torque_offset[j] = {j == 0 ? fourier.coefficients[0] : fourier.depth_slope_nm_per_m,
                              j == 0 ? 0.0 : fourier.coefficients[0], 0.0, 0.0};
      continue;
    }
    const double variation = AngleVariation(joint, j, middle);
    if (variation > 0.0) {
      notes->push_back(name + Format("the dVRK torque offset has no angle term: tau0 taken at "
                                     "q = 0 (it varies by up to %.3g N·m over ±%.3f rad)",
                                     variation, kJointRangeRad[j]));
    }
    const double low = models::BiasTorqueAt(joint, 0.0, joint.depth_min_m);
    const double high = models::BiasTorqueAt(joint, 0.0, joint.depth_max_m);
    const double slope = (high - low) / (joint.depth_max_m - joint.depth_min_m);
    if (j == 0) {
      out.torque_offset[j] = {models::BiasTorqueAt(joint, 0.0, middle), 0.0, 0.0, 0.0};
      if (slope != 0.0) {
        notes->push_back(name + Format("the dVRK torque offset of joint 1 is a constant: tau0 "
                                       "taken at L = %.3f m (its depth slope %.3g N·m/m dropped)",
                                       middle, slope));
      }
    } else {
      out.torque_offset[j] = {slope, low - slope * joint.depth_min_m, 0.0, 0.0};
    }
  }
  notes->push_back("tau_min, the dead-zone width and the depth range have no place in the dVRK "
                   "file and are not written");
  return out;
}

}  // namespace pliant::io
