#pragma once
// Model-versus-measurement diagnostics (docs/diagnose.md): compare the model's
// prediction with every measurement of a log, find where it fails (which
// channel, at which lag, explains the residual), fit every candidate effect of
// the catalogue as an extension of the model, rank them by held-out error
// reduction, and refit with the chosen ones in.
//
//   const io::Log log = io::ReadLog("divot_friction.csv");
//   const auto params = io::ReadParameters("identified.json");
//   const Diagnosis d = Diagnose(log, params, {});
//   if (d.missing_effect) std::cout << *d.missing_effect << "\n";
//
// The residual is the joint-angle error of the model where the log says where
// the tip really was: tip_fixed segments (the tip angle is one unknown per
// segment) or q1_ref/q2_ref (an external tracker). Errors are reported in rad
// per joint and in mm at the tip through the PSM kinematics.

#include <optional>
#include <string>
#include <vector>

#include "pliant/estimation/filter.h"
#include "pliant/io/log.h"
#include "pliant/models/parameters.h"

namespace pliant::estimation {

struct DiagnoseOptions {
  /// Catalogue effects to add to the model before comparing (--add NAME).
  std::vector<std::string> added_effects;
  /// Candidates to try; empty means every catalogue effect marked as a
  /// candidate (see CandidateEffectNames()).
  std::vector<std::string> candidates;
  int max_lag_samples = 30;          ///< residual–channel cross-correlation over ±this
  double family_significance = 0.05; ///< family-wise error level over all candidates (Holm)
  int folds = 5;                     ///< cross-validation folds, by segment
  FilterOptions filter;              ///< for the standardised innovations
  /// Where the tip was: "auto" (q*_ref, else tip_fixed, else q*_true),
  /// "q*_ref", "tip_fixed" or "q*_true".
  std::string reference = "auto";
  /// A joint's sample is compared only when its load exceeds this many times
  /// the model's dead-zone width (inside the clearance the shaft's place has
  /// memory the static model lacks).
  double min_load_factor = 2.0;
  /// Compared samples are thinned evenly to at most this many (speed).
  std::size_t max_samples = 6000;
  /// An effect is called missing only if it also cuts the held-out RMS by
  /// at least this fraction.
  double min_heldout_reduction = 0.15;
  /// Two material candidates are told apart when one cuts the held-out RMS
  /// left by the other by at least this fraction; below it both ways they
  /// explain the same residual and the diagnosis says it cannot tell.
  double min_unique_reduction = 0.1;
  /// At most this many material candidates enter the pairwise comparison
  /// (the best by held-out reduction); each pair costs one cross-validation.
  int max_compared_candidates = 4;
  /// Refit the model's compliance scale and clearance per joint together with
  /// every candidate (and alone, for the baseline the candidates are scored
  /// against): an identification that absorbed part of the effect then no
  /// longer hides it, and no candidate wins by correcting K or δ alone.
  bool recalibrate_base = true;
  /// When the parameters take the clearance up over a load wider than e ×
  /// tau_min (an identification can read a stiffening so), also compare the
  /// deflection candidates on the loads inside that take-up, with its width,
  /// δ and K's scale refitted (docs/diagnose-method.md). Off with --add.
  bool probe_wide_take_up = true;
  /// RMS errors are of the residual averaged over windows this long (s):
  /// the model's error, with the sensors' white noise averaged out. 0: per sample.
  double rms_window_s = 0.05;
  /// The effort's rate (for the effort_delay candidate) is the slope of a
  /// line through this window of samples (s), centred on its row: the line
  /// EffectInputs streams, read half a window later.
  double effort_rate_window_s = 0.1;
  /// Lags of the Ljung–Box test of whiteness.
  int ljung_box_lags = 20;
};

/// How well one residual series fits its noise model.
struct ResidualStatistics {
  std::size_t samples = 0;
  double rms_mm = 0.0;                ///< at the tip
  double rms_rad[2] = {0.0, 0.0};     ///< per joint
  double bias_rad[2] = {0.0, 0.0};
  double mean_nis = 0.0;              ///< filter's NIS per degree of freedom
  double nis_band[2] = {0.0, 0.0};    ///< its two-sided 95 % χ² band
  double ljung_box_q = 0.0;           ///< whiteness of the standardised innovations
  double ljung_box_p = 1.0;
  double normality_statistic = 0.0;   ///< Jarque–Bera on the standardised innovations
  double normality_p = 1.0;
};

/// One channel of the log that explains part of the residual.
struct ChannelFinding {
  std::string name;        ///< log column, or a derived one ("|tau1|", "sign(v1)", "reversal")
  int joint = 1;           ///< residual of joint 1 or 2
  int lag = 0;             ///< samples; > 0: the residual follows the channel
  double score = 0.0;      ///< fraction of residual variance explained, 0..1
  double p_value = 1.0;    ///< adjusted for the number of channels × lags tested
  std::string finding;     ///< in words: "joint 1 reads 0.8 mrad high while v1 > 0 …"
  /// A caution for the reader, or "": the best lag sits at the edge of the
  /// ±max-lag window (the true lag may be longer), or the channel is the log's
  /// time or segment number (a drift or a difference between segments, not a
  /// physical cause).
  std::string remark;
};

/// One candidate effect fitted as an extension of the model.
struct EffectFinding {
  std::string name;                  ///< catalogue key
  std::string description;           ///< its physical explanation
  std::vector<std::string> channels; ///< log channels it uses
  double score = 0.0;          ///< held-out RMS reduction, fraction (0.6 = 60 % less error)
  double p_value = 1.0;        ///< of the improvement, adjusted for the candidates tried
  double delta_aic = 0.0;      ///< AIC(with) − AIC(without); < 0 favours the effect
  double delta_bic = 0.0;
  double heldout_rms_before_mm = 0.0;
  double heldout_rms_after_mm = 0.0;
  /// RMS over the compared rows of what the fitted effect changes in the
  /// residual (tip angles profiled as the residual is), in `size_unit`: on the
  /// fitted rows size² ≈ RMS_before² − RMS_after², so a larger size is a larger
  /// in-sample reduction.
  double size = 0.0;
  double size_sd = 0.0;
  std::string size_unit;       ///< "mm" at the tip
  std::vector<std::string> parameter_names;
  std::vector<double> parameters;     ///< fitted values
  std::vector<double> parameter_sd;   ///< from ceres::Covariance
  bool missing = false;        ///< significant and large enough to call missing
  /// Held-out RMS reduction when this effect is added last, given the
  /// effects selected before it (all refitted jointly): what it explains that
  /// the others cannot. Equals `score` for the first selected effect.
  double unique_score = 0.0;
  /// Effects that explain the same residual (each removes little once the
  /// other is in), with the experiment that would separate them; empty when none.
  std::vector<std::string> indistinguishable_from;
  std::string separating_experiment;
};

/// Sample-by-sample series, for plots (one entry per log row used).
struct ResidualSeries {
  std::vector<std::size_t> row;      ///< index into the log
  std::vector<double> residual_before_rad[2];
  std::vector<double> residual_after_rad[2];  ///< with the added / best effect in
  std::vector<double> standardised_innovation;
};

struct Diagnosis {
  std::string reference;          ///< "tip_fixed", "q*_ref", "q*_true"
  double rms_before_mm = 0.0;     ///< held-out, the model as given
  double rms_after_mm = 0.0;      ///< held-out, with the added effects (or the best, if none added)
  /// Held-out, the model with its compliance scale and clearance refitted
  /// (DiagnoseOptions::recalibrate_base; else the model as given): the
  /// baseline every candidate's score is measured against.
  double rms_recalibrated_mm = 0.0;
  /// What the sensors' white noise alone leaves in these held-out RMS errors
  /// (mm): no model goes below it (docs/diagnose-method.md).
  double noise_floor_mm = 0.0;
  std::optional<std::string> missing_effect;
  ResidualStatistics before;
  ResidualStatistics after;
  std::vector<EffectFinding> effects;    ///< best first
  std::vector<ChannelFinding> channels;  ///< best first
  std::vector<std::string> added_effects;
  /// The --add effects as fitted (jointly, on every compared row): parameters ± sd.
  std::vector<EffectFinding> added;
  /// The base's compliance shares s_j (K → (1 + s_j)·K) and clearance
  /// widenings d_j (δ → δ + d_j, rad) refitted with the --add effects
  /// (compliance_share1, compliance_share2, clearance1, clearance2); empty
  /// without --add or without DiagnoseOptions::recalibrate_base.
  std::optional<EffectFinding> recalibration;
  /// Covariance of the recalibration's parameters (when present) then the
  /// --add effects', from a clustered sandwich over the segments.
  Eigen::MatrixXd added_covariance;
  /// Effects selected stepwise (each refitted with the ones before it), in order.
  std::vector<std::string> selected;
  /// What this log could not tell and why (an unrecorded joint, loads inside
  /// the clearance, …), in words.
  std::vector<std::string> notes;
  bool joint_recorded[2] = {true, true};
  int max_lag_samples = 0;  ///< the lag window the channels were tried over
  ResidualSeries series;
};

/// Catalogue effects offered as candidates (those whose effect is not part
/// of the base model).
std::vector<std::string> CandidateEffectNames();

/// Throws io::InputError for an unknown effect name, an effect given twice
/// in --add or --candidate, or one that is both added and a candidate
/// (`log_path` names the file in the unknown-name message).
void CheckEffectOptions(const DiagnoseOptions& options, const std::string& log_path);

/// Throws io::InputError when the log cannot be diagnosed (no tip_fixed
/// segment and no reference columns; an unknown effect name), naming the
/// problem and what to do.
Diagnosis Diagnose(const io::Log& log, const std::string& log_path,
                   const models::ModelParameters& parameters, const DiagnoseOptions& options);

/// The parameters with what the diagnosis fitted: each joint's K(L) scaled by
/// 1 + s_j and its clearance δ_j widened by d_j (the recalibration), and the
/// --add effects appended to `effects` with their values and sd, so that
/// `pliant correct` and the filter apply them. The covariance of each law's
/// coefficients scales with the law; the refit's variances add to δ's.
/// `source` names the log in the parameters' sources.
models::ModelParameters WithDiagnosedEffects(const models::ModelParameters& parameters,
                                             const Diagnosis& diagnosis, const std::string& source);

}  // namespace pliant::estimation
