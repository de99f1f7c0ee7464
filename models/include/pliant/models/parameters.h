#pragma once
// The parameters of the paper's model for PSM joints 1 and 2, as plain data.
// Read and written as JSON by pliant::io (docs/parameters.md).

#include <array>
#include <map>
#include <optional>
#include <string>
#include <vector>

#include <Eigen/Core>

#include "pliant/models/cubic.h"

namespace pliant::models {

/// How a compliance cubic is written.
enum class ComplianceForm {
  kInverseCubic,  ///< the paper's: 1/K(L) = c3·L³ + c2·L² + c1·L + c0, in N·m/rad
  kDirectCubic,   ///< the dVRK parameter file's: K(L) = a·L³ + b·L² + c·L + d, in rad/(N·m)
};

/// Compliance K(L) of one joint (rad/(N·m)) as a function of insertion depth L (m).
struct ComplianceLaw {
  ComplianceForm form = ComplianceForm::kInverseCubic;
  Cubic cubic;
};

/// Bias torque tau0(q) of one joint: the paper's calibration table, effort
/// averaged at each joint angle (5° steps), linearly interpolated between
/// angles and held constant beyond the ends.
struct BiasTorqueTable {
  std::vector<double> angle_rad;  ///< strictly increasing
  std::vector<double> torque_nm;  ///< same length
};

struct JointParameters {
  BiasTorqueTable bias_torque;
  ComplianceLaw compliance;
  double backlash_rad = 0.0;       ///< delta: half the cannula clearance, as an angle
  double tau_min_nm = 0.0;         ///< the paper's switch threshold (equation 2)
  double deadzone_width_nm = 0.0;  ///< torque that takes up the clearance (dead-zone model)
  double depth_min_m = 0.0;        ///< the depth range the fit is valid on
  double depth_max_m = 0.0;
  std::map<std::string, std::string> sources;  ///< where each value comes from
};

/// Optional covariance of named parameters (e.g. "joint1.backlash_rad").
struct ParameterCovariance {
  std::vector<std::string> names;
  Eigen::MatrixXd matrix;
};

struct ModelParameters {
  std::string description;
  std::array<JointParameters, 2> joints;  ///< [0] joint 1 (yaw), [1] joint 2 (pitch)
  std::optional<ParameterCovariance> covariance;
};

/// Compliance K (rad/(N·m)) of a law at depth L (m), no clamping.
template <typename T>
T EvaluateCompliance(ComplianceForm form, const T* coefficients, const T& depth_m) {
  const T p = Horner3(coefficients, depth_m);
  return form == ComplianceForm::kInverseCubic ? T(1.0) / p : p;
}

/// Why a parameter set cannot be used, or an empty string when it can. Checks
/// that tables are well formed and that K(L) is finite and positive over the
/// whole valid depth range (the paper's 1/K2 crosses zero near L = 0.014 m).
std::string ValidateParameters(const ModelParameters& parameters);

/// Compliance K (rad/(N·m)) of joint `joint` (0 or 1) at depth L, clamped to
/// the joint's valid depth range.
double ComplianceAt(const JointParameters& joint, double depth_m);

}  // namespace pliant::models
