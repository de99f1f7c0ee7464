#pragma once
// The joint smoother: one Ceres problem over every sample of the logs.
//
// Per joint j and sample i (the model of pliant/models/effect.h):
//   effort   tau_meas_ij = tau0_j(q_ij, L_i) + tau_ext_ij               + noise
//   angle    q_ij        = tip_sj + delta_j·S(tau_ext_ij / w_j) + K_j(L_i)·tau_ext_ij + noise
// with tau0 the Fourier bias (BiasTorqueFourierEffect), K the chosen law
// (ComplianceEffect), the dead-zone backlash (BacklashDeadZoneEffect), tip_sj
// the latent tip angle of tip_fixed segment s, and tau_ext_ij a latent
// external torque (zero, not estimated, while the tip is free). Unknowns: the
// law's coefficients, delta_j, log w_j, the bias coefficients (global, with
// Gaussian priors) and the latents (eliminated by the Schur complement);
// log w_j is held in each solve and profiled outside it.
// Residuals pass through a Huber loss, so that a few bad samples do not drag
// the fit. The covariance of the global parameters comes from
// ceres::Covariance, scaled by the variance factor of the fit.
//
//   JointSmootherOptions options;
//   options.law = models::ComplianceForm::kBeamSeries;
//   std::string why;
//   if (!options.IsValid(&why)) ...;
//   IdentificationResult r = RunJointSmoother(data, prior, options);
//   std::cout << r.report;   // one line per solve, like ceres' BriefReport()

#include <array>
#include <string>

#include "pliant/estimation/identification.h"

namespace pliant::estimation {

struct JointSmootherOptions {
  models::ComplianceForm law = models::ComplianceForm::kInverseCubic;
  int bias_harmonics = 2;                  ///< Fourier terms of tau0(q) per joint
  bool bias_depth_term = true;             ///< tau0 linear in L (else its slope is held at 0)
  /// true: the first harmonic's growth with depth (c1, d1) is fitted for each
  /// joint whose free-tip rows determine it (sweeps at two or more depths
  /// spanning the angle), held at the prior elsewhere; false: held everywhere.
  bool bias_depth_harmonic = true;
  double bias_reference_depth_m = 0.155;
  /// Noise before the fit rescales it (per sample of one log row; a hold of n
  /// rows gets sd/√n). The encoder sd is the Classic PSM count / √12.
  double effort_noise_nm = 0.01;
  double encoder_noise_rad = 7.7e-6 / 3.4641016151377544;
  /// Huber threshold in standard deviations: residuals beyond it count linearly.
  double robust_loss_sd = 3.0;
  /// Prior standard deviations are multiplied by this (1: the effects' own).
  double prior_scale = 1.0;
  double cannula_length_m = 0.025;  ///< beam_series geometry (not fitted)
  /// The dead-zone width w is bounded below by this many effort-noise sd of
  /// one held-tip sample: a sharper take-up cannot be seen through the noise,
  /// and a hard contact would drive w to 0, where the smooth dead zone becomes
  /// a step that Levenberg–Marquardt crawls along (docs/identification-method.md).
  double deadzone_resolution_sd = 4.0;
  /// true (default): w_j is profiled above that floor, joint by joint (one
  /// extra solve on a hard wall, ~20 on a smooth take-up), and its uncertainty
  /// is carried into the others' σ (docs/decisions/0010-…); false: held at the floor.
  bool estimate_deadzone_width = true;
  int max_iterations = 100;
  int threads = 1;
  /// A parameter whose posterior sd exceeds this fraction of its prior sd is
  /// reported as not determined by the logs.
  double identified_fraction = 0.5;
  PaperProcedureOptions paper;      ///< initial values, branch thresholds, depth grouping

  bool IsValid(std::string* error) const;
};

/// `prior` is the parameter set the priors are centred on (data/paper.json
/// by default in the CLI) and supplies tau_min. Throws std::invalid_argument
/// for invalid options and std::runtime_error when Ceres fails.
IdentificationResult RunJointSmoother(const IdentificationData& data,
                                      const models::ModelParameters& prior,
                                      const JointSmootherOptions& options = {});

}  // namespace pliant::estimation
