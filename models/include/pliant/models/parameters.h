#pragma once
// The parameters of the paper's model for PSM joints 1 and 2, as plain data.
// Read and written as JSON by pliant::io (docs/parameters.md).

#include <array>
#include <cstdint>
#include <cmath>
#include <map>
#include <optional>
#include <string>
#include <vector>

#include <Eigen/Core>

#include "pliant/models/cubic.h"

namespace pliant::models {

/// How a compliance law is written.
enum class ComplianceForm {
  kInverseCubic,  ///< the paper's: 1/K(L) = c3·L³ + c2·L² + c1·L + c0, in N·m/rad
  kDirectCubic,   ///< the dVRK parameter file's: K(L) = a·L³ + b·L² + c·L + d, in rad/(N·m)
  /// From mechanics (docs/identification.md): three compliances in series,
  ///   K(L) = c_joint + c_structure / L + f_shaft · (L − l_c)³₊ / (3 L²),
  /// the joint's torsion, the arm tilting under the lateral force F = tau/L,
  /// and the shaft bending as a cantilever beyond the cannula tip (tip
  /// deflection F·l³/(3EI), l = L − l_c, seen as an angle at the RCM).
  kBeamSeries,
};

/// The four numbers of a kBeamSeries law, in the order they are stored.
enum BeamSeriesCoefficient {
  kJointComplianceRadPerNm = 0,      ///< c_joint, rad/(N·m)
  kStructureComplianceRadPerN = 1,   ///< c_structure, rad/N
  kShaftFlexibilityPerNm2 = 2,       ///< f_shaft = 1/(EI), 1/(N·m²)
  kCannulaLengthM = 3,               ///< l_c: RCM to cannula tip, m (geometry, not fitted)
};

/// Compliance K(L) of one joint (rad/(N·m)) as a function of insertion depth L (m).
/// `cubic.coefficients` holds the cubic's {c3, c2, c1, c0}, or for kBeamSeries
/// the four numbers indexed by BeamSeriesCoefficient.
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

/// A smooth bias torque: a short Fourier series in the joint's own angle q
/// plus terms in the insertion depth L. The instrument's centre of mass moves
/// along the shaft as it is inserted, so both the level (s) and the gravity
/// moment's first harmonic (its arm grows with L: c1, d1) change with depth:
///   tau0(q, L) = a0 + Σ_k [a_k·cos(k·q) + b_k·sin(k·q)]
///                + (L − L_ref)·(s + c1·cos q + d1·sin q)
struct BiasTorqueFourier {
  std::vector<double> coefficients;  ///< a0, a1, b1, a2, b2, … (N·m); odd length
  double depth_slope_nm_per_m = 0.0;  ///< s
  double reference_depth_m = 0.155;   ///< L_ref, the middle of the paper's depth range
  /// c1, d1 (N·m/m): the first harmonic's growth with depth (0 in files without it)
  std::array<double, 2> depth_harmonic_nm_per_m{{0.0, 0.0}};
};

enum class BiasForm {
  kTable,    ///< the paper's table (BiasTorqueTable)
  kFourier,  ///< BiasTorqueFourier
};

struct JointParameters {
  BiasForm bias_form = BiasForm::kTable;
  BiasTorqueTable bias_torque;     ///< used when bias_form is kTable
  BiasTorqueFourier bias_fourier;  ///< used when bias_form is kFourier
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

/// One catalogue effect the parameters carry beyond the paper's model (e.g.
/// "held_friction"), with every parameter of the effect, in the effect's
/// order (estimation::ExtraEffects checks them against the catalogue).
struct EffectParameters {
  std::string name;
  std::vector<std::string> parameter_names;
  std::vector<double> values;
  std::vector<double> sd;  ///< 0 for a parameter held at its value
};

/// A log the parameters were fitted on (`pliant identify`, `diagnose
/// --write-params`): the path as given and the CRC-32 of its bytes, so that a
/// diagnosis can tell when it reads the very log the parameters took an effect
/// up from (docs/parameters.md, "identified_from").
struct SourceLog {
  std::string file;
  std::uint32_t crc32 = 0;
};

struct ModelParameters {
  std::string description;
  std::vector<SourceLog> identified_from;  ///< empty: not recorded (a hand-written file)
  std::array<JointParameters, 2> joints;  ///< [0] joint 1 (yaw), [1] joint 2 (pitch)
  std::optional<ParameterCovariance> covariance;
  std::vector<EffectParameters> effects;  ///< applied by correct and the filter alike
};

/// Compliance K (rad/(N·m)) of a law at depth L (m), no clamping.
template <typename T>
T EvaluateCompliance(ComplianceForm form, const T* coefficients, const T& depth_m) {
  if (form == ComplianceForm::kBeamSeries) {
    // Series compliances add. The shaft bends only where it leaves the cannula.
    const T free_length = depth_m - coefficients[kCannulaLengthM];
    const T shaft = free_length > 0.0 ? free_length * free_length * free_length /
                                            (T(3.0) * depth_m * depth_m)
                                      : T(0.0);
    return coefficients[kJointComplianceRadPerNm] +
           coefficients[kStructureComplianceRadPerN] / depth_m +
           coefficients[kShaftFlexibilityPerNm2] * shaft;
  }
  const T p = Horner3(coefficients, depth_m);
  return form == ComplianceForm::kInverseCubic ? T(1.0) / p : p;
}

/// tau0 (N·m) of a Fourier bias at joint angle q (rad) and depth L (m);
/// `coefficients` as in BiasTorqueFourier, `harmonics` = (size − 1) / 2,
/// `depth_harmonic_nm_per_m` points at c1, d1.
template <typename T>
T EvaluateFourierBias(const T* coefficients, int harmonics, const T& depth_slope_nm_per_m,
                      const T* depth_harmonic_nm_per_m, double reference_depth_m,
                      const T& angle_rad, const T& depth_m) {
  using std::cos;
  using std::sin;
  const T per_depth = depth_slope_nm_per_m + depth_harmonic_nm_per_m[0] * cos(angle_rad) +
                      depth_harmonic_nm_per_m[1] * sin(angle_rad);
  T sum = coefficients[0] + per_depth * (depth_m - reference_depth_m);
  for (int k = 1; k <= harmonics; ++k) {
    sum += coefficients[2 * k - 1] * cos(double(k) * angle_rad) +
           coefficients[2 * k] * sin(double(k) * angle_rad);
  }
  return sum;
}

/// Why a parameter set cannot be used, or an empty string when it can. Checks
/// that tables are well formed and that K(L) is finite and positive over the
/// whole valid depth range (the paper's 1/K2 crosses zero near L = 0.014 m).
std::string ValidateParameters(const ModelParameters& parameters);

/// Compliance K (rad/(N·m)) of joint `joint` (0 or 1) at depth L, clamped to
/// the joint's valid depth range.
double ComplianceAt(const JointParameters& joint, double depth_m);
/// Both joints' K (rad/(N·m)) at depth L: what a deflection effect reads as
/// JointState::compliance_rad_per_nm.
Eigen::Vector2d CompliancesAt(const std::array<JointParameters, 2>& joints, double depth_m);

/// tau0 (N·m) of a joint at its angle q (rad) and depth L (m), in either form.
double BiasTorqueAt(const JointParameters& joint, double angle_rad, double depth_m);

/// Scales a law's K(L) by `scale` at every depth, whatever its form (the
/// beam series' geometry l_c stays).
void ScaleCompliance(ComplianceLaw& law, double scale);

/// "inverse_cubic", "direct_cubic", "beam_series" (the parameters file's words).
const char* ComplianceFormName(ComplianceForm form);

/// The form a name of ComplianceFormName's stands for; false for any other name.
bool ComplianceFormNamed(const std::string& name, ComplianceForm* form);

}  // namespace pliant::models
