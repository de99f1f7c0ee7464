#pragma once
// The paper's correction of PSM joints 1 and 2, sample by sample, with no
// memory and no uncertainty: the baseline every later estimator is measured
// against.
//
//   tau_ext = tau_meas − tau0(q)              (bias torque: table or Fourier series)
//   paper:    q̂ = q − [δ·sgn(tau_ext) + K(L)·tau_ext]  if |tau_ext| > tau_min,
//             q̂ = q                                    otherwise   (paper eq. 2)
//   deadzone: q̂ = q − [δ·S(tau_ext / w) + K(L)·tau_ext]             (no switch)
//
// S is the smooth saturation of pliant/models/smooth.h; w is the dead-zone
// width (by default the paper's tau_min). Equation (2) jumps by
// δ + K(L)·tau_min as |tau_ext| crosses tau_min; the dead-zone form is
// continuous in tau_ext (docs/correction.md). L is clamped to the valid range.
//
// Effects the parameters file carries beyond the paper's ("effects",
// extra_effects.h) are applied too: internal torques leave the effort before
// tau_ext is read, deflections join K(L)·tau_ext. An effect that reads the
// travel since the last reversal (held_friction) needs the row history:
// pass it from a models::TravelSinceReversal fed with every row.

#include <optional>
#include <string_view>
#include <vector>

#include <Eigen/Core>

#include "pliant/models/effects/backlash.h"
#include "pliant/models/effects/bias_torque.h"
#include "pliant/models/effects/bias_torque_fourier.h"
#include "pliant/estimation/extra_effects.h"
#include "pliant/models/effects/compliance.h"
#include "pliant/models/parameters.h"

namespace pliant::estimation {

enum class CorrectionModel {
  kPaper,     ///< equation (2): sgn backlash behind the tau_min switch
  kDeadZone,  ///< continuous dead-zone backlash, no switch
};

/// "paper" or "deadzone"; nullopt for anything else.
std::optional<CorrectionModel> ParseCorrectionModel(std::string_view name);

struct JointCorrection {
  Eigen::Vector2d corrected_rad;       ///< q̂1, q̂2
  Eigen::Vector2d external_torque_nm;  ///< tau_ext = tau_meas − tau0(q)
  Eigen::Vector2d deflection_rad;      ///< q − q̂
  bool depth_clamped = false;          ///< L was outside the valid range of a joint whose angle the row has
};

class ComplianceCorrector {
 public:
  /// Parameters must pass models::ValidateParameters (throws
  /// std::invalid_argument with its message otherwise).
  ComplianceCorrector(const models::ModelParameters& parameters, CorrectionModel model);

  /// q = (q1 rad, q2 rad, q3 m); measured_torque_nm = (tau1, tau2).
  /// travel_since_reversal_rad: models::TravelSinceReversal's output for
  /// this row (zero when no effect of the file reads it).
  JointCorrection Correct(const Eigen::Vector3d& q, const Eigen::Vector2d& measured_torque_nm,
                          const Eigen::Vector2d& travel_since_reversal_rad =
                              Eigen::Vector2d::Zero()) const;
  /// The same with every input the file's effects may read (EffectInputs:
  /// velocity, time, the effort's rate), its external torque ignored.
  JointCorrection Correct(const models::JointState<double>& inputs,
                          const Eigen::Vector2d& measured_torque_nm) const;

  const ExtraEffects& extra_effects() const { return extra_; }

  /// Size of equation (2)'s jump at |tau_ext| = tau_min for joint j (0 or 1), at
  /// depth L: δ + K(L)·tau_min (rad). Zero for the dead-zone model.
  double JumpAtThreshold(int joint, double depth_m) const;

 private:
  models::ModelParameters parameters_;
  CorrectionModel model_;
  models::BiasTorqueEffect bias_;                 // joints whose bias is a table
  models::BiasTorqueFourierEffect bias_fourier_;  // joints whose bias is a Fourier series
  models::ComplianceEffect compliance_;
  models::BacklashSignEffect backlash_sign_;
  models::BacklashDeadZoneEffect backlash_deadzone_;
  ExtraEffects extra_;
  std::vector<double> bias_values_, fourier_values_, compliance_values_, sign_values_, deadzone_values_;
};

}  // namespace pliant::estimation
