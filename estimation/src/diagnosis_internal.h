#pragma once
// Shared pieces of Diagnose() (estimation/diagnosis.h), split by job:
//   diagnosis_data.cpp        which rows, which reference, the base model's residual
//   diagnosis_statistics.cpp  Ljung–Box, Jarque–Bera, effective sample size, Holm
//   diagnosis_channels.cpp    where the residual comes from (channels × lags)
//   diagnosis_costs.cpp       Ceres fit of effects as extensions of the model (the only
//                             translation unit with Jets in a cost)
//   diagnosis_take_up.cpp     the loads inside a wide take-up, the take-up refitted
//   diagnosis.cpp             the whole diagnosis
#include <algorithm>
#include <array>
#include <cstddef>
#include <functional>
#include <memory>
#include <string>
#include <type_traits>
#include <vector>

#include <Eigen/Core>
#include <ceres/problem.h>

#include "diagnosis_statistics.h"
#include "pliant/estimation/diagnosis.h"
#include "pliant/estimation/effect_catalogue.h"
#include "pliant/estimation/effect_fit.h"
#include "pliant/io/log.h"
#include "pliant/models/effects/backlash.h"
#include "pliant/models/effects/compliance.h"
#include "pliant/models/parameters.h"

namespace pliant::estimation::diagnosis {

/// One log row the diagnosis compares.
struct Sample {
  std::size_t row = 0;
  models::JointState<double> state;  ///< external torque: tau_meas − tau0 (no effects)
  Eigen::Vector2d reference_rad{0.0, 0.0};  ///< tip angle; 0 when profiled (tip_fixed)
  int group = 0;                     ///< segment (or time block): the CV unit
  int tip_group = 0;                 ///< run of tip_fixed rows: one unknown tip angle
  std::array<bool, 2> used{false, false};  ///< joint loaded beyond the clearance
  Eigen::Vector2d mm_per_rad{0.0, 0.0};    ///< tip displacement per joint error
};

/// An effect with its parameters, as part of a model.
struct Term {
  std::shared_ptr<const EffectModel> effect;
  std::vector<double> parameters;
  std::string name;
  /// The base model's recalibration only: K_j(L) as it refits it (rad/(N·m)),
  /// which the deflection effects that scale with the compliance then read.
  std::function<Eigen::Vector2d(const double*, double)> compliance;
  std::function<models::Vec2<EffectJet>(const EffectJet*, double)> compliance_jet;
};

/// The rows, their reference and the noise scale that standardises residuals.
struct Problem {
  std::string reference;    ///< "q*_ref", "q*_true", "tip_fixed"
  bool profile_tip = false; ///< tip angle unknown: one per group, profiled out
  std::vector<Sample> samples;
  int groups = 0;
  int tip_groups = 0;
  std::vector<int> fold_of_group;
  double rms_window_s = 0.0;  ///< residuals averaged over this before an RMS
  int folds = 1;
  Eigen::Vector2d noise_sd_rad{1e-3, 1e-3};  ///< measurement noise of the residual
  bool joint_recorded[2] = {true, true};    ///< false: the joint stays at its prior, unused
  bool quasi_static = false;  ///< rows are poses: no time, motion or effort rate is read
  /// Terms refitted with every candidate and in the baseline it is scored
  /// against (the base model's recalibration), empty when off.
  std::vector<Term> refit;
  /// Terms refitted with the added effects (`--add`, identify --effect): the
  /// recalibration with K's depth tilt as well, empty when off.
  std::vector<Term> added_refit;
  std::vector<std::string> notes;           ///< what the log cannot tell, in words
};

/// The model the diagnosis compares: the parameters' bias (already removed
/// from Sample::state), compliance and dead-zone backlash, plus effect terms.
class BaseModel {
 public:
  /// The parameters' model with the effects the file holds, at their values,
  /// but those named in `refitted` (fitted again as added terms).
  explicit BaseModel(const models::ModelParameters& parameters,
                     const std::vector<std::string>& refitted = {});

  /// Encoder minus tip angle the model predicts, given the external torque:
  /// compliance, dead zone and the file's deflection effects.
  template <typename T>
  models::Vec2<T> BaseDeflection(const models::JointState<T>& state) const {
    std::array<T, 8> law;
    for (int i = 0; i < 8; ++i) law[i] = T(compliance_values_[i]);
    const T backlash[4] = {T(deadzone_values_[0]), T(deadzone_values_[1]),
                           T(deadzone_values_[2]), T(deadzone_values_[3])};
    models::Vec2<T> deflection = compliance_(law.data(), state) + deadzone_(backlash, state);
    for (std::size_t i = 0; i < file_effects_.size(); ++i) {
      if (file_effects_[i].effect->Info().channel == models::Channel::kDeflection)
        deflection += file_effects_[i].effect->Evaluate(FileValues<T>(i), state);
    }
    return deflection;
  }
  /// Takes the internal torque of the file's effects out of the state's
  /// external torque (the measured effort less the bias).
  template <typename T>
  void TakeOutInternalTorque(models::JointState<T>* state) const {
    for (std::size_t i = 0; i < file_effects_.size(); ++i) {
      if (file_effects_[i].effect->Info().channel == models::Channel::kInternalTorque)
        state->external_torque_nm -= file_effects_[i].effect->Evaluate(FileValues<T>(i), *state);
    }
  }
  /// The effects of the parameters file in the model (not candidates).
  const std::vector<Term>& file_effects() const { return file_effects_; }
  /// The width the model's dead zone takes the clearance up over (N·m).
  double clearance_load_nm(int joint) const { return clearance_load_nm_[joint]; }
  /// The load a row's compared beyond (times DiagnoseOptions::min_load_factor):
  /// the clearance load, unless the take-up probe narrows it.
  double compared_load_nm(int joint) const { return compared_load_nm_[joint]; }
  void set_compared_load_nm(int joint, double load_nm) { compared_load_nm_[joint] = load_nm; }
  const models::ModelParameters& parameters() const { return parameters_; }

 private:
  template <typename T>
  const T* FileValues(std::size_t i) const {
    if constexpr (std::is_same_v<T, double>) {
      return file_effects_[i].parameters.data();
    } else {
      return file_jets_[i].data();
    }
  }

  models::ModelParameters parameters_;
  std::vector<Term> file_effects_;
  std::vector<std::vector<EffectJet>> file_jets_;  // the same values, constant Jets
  models::ComplianceEffect compliance_;
  models::BacklashDeadZoneEffect deadzone_;
  std::vector<double> compliance_values_;
  double deadzone_values_[4];
  double clearance_load_nm_[2];
  double compared_load_nm_[2];
};

/// Encoder − reference − predicted deflection (rad) of one sample with
/// `terms` in the model, their parameters at `values[i]` (T = double or
/// EffectJet). Internal-torque terms change the external torque the
/// deflection sees; deflection terms add to it.
template <typename T>
models::Vec2<T> ModelResidual(const Sample& sample, const BaseModel& model,
                              const std::vector<Term>& terms, const std::vector<const T*>& values) {
  // The parameters' K(L) is in the sample's state (BuildProblem); a refitted
  // one replaces it.
  models::JointState<T> state = sample.state.Cast<T>();
  const double depth = sample.state.insertion_depth_m;
  for (std::size_t i = 0; i < terms.size(); ++i) {
    if constexpr (std::is_same_v<T, double>) {
      if (terms[i].compliance) state.compliance_rad_per_nm = terms[i].compliance(values[i], depth);
    } else {
      if (terms[i].compliance_jet) state.compliance_rad_per_nm = terms[i].compliance_jet(values[i], depth);
    }
  }
  model.TakeOutInternalTorque(&state);
  for (std::size_t i = 0; i < terms.size(); ++i) {
    if (terms[i].effect->Info().channel == models::Channel::kInternalTorque)
      state.external_torque_nm -= terms[i].effect->Evaluate(values[i], state);
  }
  models::Vec2<T> deflection = model.BaseDeflection(state);
  for (std::size_t i = 0; i < terms.size(); ++i) {
    if (terms[i].effect->Info().channel == models::Channel::kDeflection)
      deflection += terms[i].effect->Evaluate(values[i], state);
  }
  models::Vec2<T> residual;
  for (int j = 0; j < 2; ++j) {
    residual[j] = T(sample.state.encoder_angle_rad[j] - sample.reference_rad[j]) - deflection[j];
  }
  return residual;
}

/// Residual (encoder − tip − predicted deflection) of every sample, rad, with
/// `terms` in the model. Under tip_fixed the per-group mean is removed (the
/// tip angle profiled out, over the samples of the groups in `only`, when
/// given). Entries of unused joints are 0.
std::vector<Eigen::Vector2d> Residuals(const Problem& problem, const BaseModel& model,
                                       const std::vector<Term>& terms,
                                       const std::vector<bool>* only = nullptr);

/// Under tip_fixed, removes each tip group's mean per joint, computed over the
/// samples of the CV groups in `only` (all when null) and removed from them.
void ProfileGroups(const Problem& problem, std::vector<Eigen::Vector2d>& residual,
                   const std::vector<bool>* only = nullptr);

/// A time step (s) beyond which the effects see a pose change, not motion:
/// the filter's, so that both read a log's gaps alike.
inline const double kTimeGapS = FilterOptions{}.time_gap_s;

/// When the parameters were fitted on this very log (their identified_from
/// holds its CRC-32), a note that what the fit took up cannot show here.
void NoteFittedOnThisLog(const models::ModelParameters& parameters, const std::string& log_path,
                         std::vector<std::string>* notes);
/// Builds the problem from a log. Throws io::InputError when there is no
/// reference (no tip_fixed rows, no q*_ref / q*_true columns).
Problem BuildProblem(const io::Log& log, const std::string& log_path, const BaseModel& model,
                     const std::vector<Term>& added, const DiagnoseOptions& options);

/// Sets problem->folds (≤ wanted, ≥ 2 where there are 2 groups) and deals the
/// groups to them stratified: by the scarcest joint a group loads, then by
/// depth, so every fold's training groups span each joint's depths.
void AssignFolds(int wanted_folds, Problem* problem);

/// Tip RMS (mm), sqrt(mean e1² + mean e2²) over each joint's used samples of the groups
/// where `keep(group)`, each joint's residual first averaged over consecutive windows of
/// Problem::rms_window_s (the model's error, the sensors' white noise averaged out).
double TipRmsMm(const Problem& problem, const std::vector<Eigen::Vector2d>& residual,
                const std::vector<bool>* keep_group = nullptr);
/// What the sensors' white noise alone leaves in TipRmsMm (mm): its variance
/// per sample, from the residual's steps between neighbouring samples, over
/// each joint's samples per window.
double NoiseFloorMm(const Problem& problem, const std::vector<Eigen::Vector2d>& residual);

// --- fitting -------------------------------------------------------------------
struct FitResult {
  std::vector<std::vector<double>> parameters;  ///< per fitted term
  std::vector<std::vector<double>> parameter_sd;
  bool covariance_ok = false;
  Eigen::MatrixXd covariance;  ///< over all fitted parameters, term by term
  Eigen::MatrixXd white_covariance;  ///< the same, rows taken as independent (before `clustered`)
};

/// Least squares of the standardised residual over the samples of groups
/// where `train_group`, with `fixed` terms in the model and `fitted` terms'
/// parameters free (bounds and Gaussian priors of their ParameterSpecs).
/// Covariance (when `covariance`) is scaled by 1/effective-size factor;
/// `clustered`: the cluster jackknife with each CV group (segment) as one
/// draw, never below the white-noise covariance (the rows of one push are
/// correlated; docs/decisions/diagnosis-sd-by-segment-jackknife.md).
FitResult FitTerms(const Problem& problem, const BaseModel& model, const std::vector<Term>& fixed,
                   const std::vector<Term>& fitted, const std::vector<bool>& train_group,
                   bool covariance, double size_factor, bool clustered = false);

/// What the base model's recalibration frees: K's scale s_j and the
/// clearance d_j (with each candidate); with K's depth tilt u_j as well (with
/// the added effects); or with the tilt and the dead zone's take-up width,
/// e^l_j times the model's (the take-up probe, diagnosis_take_up.cpp).
/// (kNarrowTakeUp: the width starts at, and its prior is about, a clearance's
/// take-up, NarrowTakeUpNm).
enum class Recalibration { kScale, kTilt, kTakeUp, kNarrowTakeUp };
/// The load the diagnosis's dead zone takes the clearance up over (N·m): the
/// parameters' width, never below tau_min or 0.05 N·m.
double ClearanceLoad(const models::JointParameters& joint);
/// The load a cannula clearance is taken up over, the width an identification
/// starts from: the parameters' tau_min, at least 0.05 N·m.
inline double NarrowTakeUpNm(const models::JointParameters& joint) {
  return std::max(joint.tau_min_nm, 0.05);
}
/// A take-up wider than e × NarrowTakeUpNm (the identification's prior on its
/// log has sd 1) is one the take-up probe looks into (diagnosis_take_up.cpp).
inline constexpr double kWideTakeUpFactor = 2.718281828459045;
/// The base model's compliance share and clearance as a term to refit with
/// each candidate (DiagnoseOptions::recalibrate_base); `model` must outlive
/// it. Its parameters: s1, s2, d1, d2, then u1, u2 (all but kScale), then
/// l1, l2 (the take-up kinds).
Term BaseRecalibrationTerm(const BaseModel& model, Recalibration kind);
/// Problem::refit and Problem::added_refit of the base model, or none.
void SetRecalibration(const BaseModel& model, bool on, Problem* problem);

/// The change of a joint's stored law coefficients (the law's order) per unit
/// of the recalibration's depth tilt u, before its scale 1 + s: with x the
/// depth across the parameters' range (−1 … +1) and K_mid = K at its middle,
/// an inverse cubic becomes 1/K − u·x/K_mid, a direct cubic K + u·x·K_mid —
/// each its own form, so a parameters file holds the tilted law exactly. A
/// beam series has no such term (its shape is geometry): zero, u is not read.
std::array<double, 4> CompliancePerTilt(const models::JointParameters& joint);

/// RMS (mm at the tip) over the samples of what `term` changes in the
/// residual of the model with `fixed` (tip angles profiled like the residual),
/// and its standard deviation by the delta method.
std::array<double, 2> ContributionSizeMm(const Problem& problem, const BaseModel& model,
                                         const std::vector<Term>& fixed, const Term& term,
                                         const Eigen::MatrixXd& covariance);

// --- the effects fitted into the model (effect_fit.cpp) ------------------------
/// A catalogue effect at its default parameters.
Term MakeTerm(const std::string& name);
/// The log channels an effect reads, in the log's names.
std::vector<std::string> ChannelsOf(const EffectModel& effect);
/// The catalogue's Gaussian prior ((p − default)/prior_sd) and bounds on
/// `block`, an effect's parameters in a Ceres problem (model-based rows: the
/// clustered sandwich keeps them out of every cluster).
ceres::ResidualBlockId AddEffectPrior(ceres::Problem* problem, double* block,
                                      const EffectModel& effect);
/// `added` fitted jointly (with problem.added_refit) on every compared row, their
/// σ from a clustered sandwich over the segments; `fixed` receives them at
/// the fitted values.
FittedEffects FitAdded(const Problem& problem, const BaseModel& model,
                       const std::vector<Term>& added, std::vector<Term>* fixed);

// --- selection (diagnosis_selection.cpp) ------------------------------------------
/// Held-out residual: each fold's samples under parameters fitted on the
/// others (none fitted: the model as it is, profiled the same way, so that
/// before and after are compared alike).
std::vector<Eigen::Vector2d> CrossValidated(const Problem& problem, const BaseModel& model,
                                            const std::vector<Term>& fixed,
                                            const std::vector<Term>& fitted);
/// Per CV group, ln(SS_before / SS_after) of the tip-weighted sums of squares
/// of `before` and `after`: the blocks of BlockImprovementTest. Relative, so
/// that segments whose errors differ by orders of magnitude (an effect that
/// grows with time, load or depth) weigh alike.
std::vector<double> GainPerGroup(const Problem& problem, const std::vector<Eigen::Vector2d>& before,
                                 const std::vector<Eigen::Vector2d>& after);

/// A candidate effect with its parameters fitted on every compared row.
struct CandidateFit {
  EffectFinding finding;  ///< score, p_value (adjusted) and missing already set
  Term term;
  std::vector<Term> refit;  ///< Problem::refit as fitted with it
  /// Scored on the take-up probe's rows (ProbeWideTakeUp), not on the log's
  /// own held-out segments: its held-out RMS is not this log's.
  bool scored_on_probe_rows = false;
};

/// A candidate alone as an extension of the model (fixed terms in, the
/// problem's refit freed with it): its held-out reduction against
/// `heldout_before` (RMS `rms_before_mm`), the segment-block test of the gain
/// (unadjusted), and its fit on every row; `before` is the baseline's
/// residual, which the size is measured from.
CandidateFit EvaluateCandidate(const Problem& problem, const BaseModel& model,
                               const std::vector<Term>& fixed, const Term& candidate,
                               const std::vector<Eigen::Vector2d>& before,
                               const std::vector<Eigen::Vector2d>& heldout_before,
                               double rms_before_mm);

/// `problem.refit` followed by `terms`: what a fit with these terms frees.
std::vector<Term> WithRefit(const Problem& problem, const std::vector<Term>& terms);
/// `problem.added_refit` followed by the added effects.
std::vector<Term> WithAddedRefit(const Problem& problem, const std::vector<Term>& added);
/// Ranks the candidates by what each explains that the others cannot: the
/// material ones (missing by score and p) are fitted in pairs, cross-validated,
/// and each is scored by its smallest held-out gain when added to another
/// (EffectFinding::unique_score); those that add little both ways are marked
/// indistinguishable, with the experiment that would separate them. Sorts
/// `candidates` best first and returns the effects selected (unique gain at
/// least options.min_unique_reduction), best first.
std::vector<std::string> RankBySeparation(const Problem& problem, const BaseModel& model,
                                          const std::vector<Term>& fixed,
                                          const DiagnoseOptions& options,
                                          std::vector<CandidateFit>& candidates);

/// RMS at the tip (mm) over each joint's used samples of a − b, per sample
/// (no windows): the size of what a fit changes in the residual.
double RmsDifferenceMm(const Problem& problem, const std::vector<Eigen::Vector2d>& a,
                       const std::vector<Eigen::Vector2d>& b);

/// The condition (depth, load, hold time, motion) under which two fitted
/// effects' predictions differ most, in words with both predictions.
std::string SeparatingExperiment(const Problem& problem, const BaseModel& model,
                                 const std::vector<Term>& fixed, const Term& a, const Term& b);

// --- the take-up probe (diagnosis_take_up.cpp) -----------------------------------
struct TakeUpProbe {
  /// Deflection candidates compared on the loads from twice tau_min, each with
  /// the base's K scale, δ and take-up width refitted, against that refit
  /// alone; best first, p Holm-adjusted, `missing` set. Empty when no joint's
  /// take-up is wide.
  std::vector<CandidateFit> candidates;
  std::vector<std::string> notes;  ///< what was compared and found, in words
};
/// When a recorded joint's dead-zone width exceeds e × max(tau_min, 0.05 N·m),
/// rows are compared from the clearance's take-up on (the model's compared
/// load narrowed); false, and the model untouched, when no take-up is wide.
bool CompareInsideWideTakeUp(std::array<bool, 2> recorded, BaseModel* model);
/// The joints a log records.
std::array<bool, 2> Recorded(const io::Log& log);
/// With an added deflection effect (--add, identify --effect) on such a
/// take-up: the rows compared as the probe compares them, and true.
bool RefitTakeUpWithAdded(std::array<bool, 2> recorded, const std::vector<Term>& added,
                          BaseModel* model);
/// The added effects then fitted with the take-up refitted from a
/// clearance's (Recalibration::kNarrowTakeUp), and a note saying so; false
/// (nothing changed) when no recalibration was asked for.
bool FitAddedWithTheTakeUp(const BaseModel& model, Problem* problem);
/// Runs when a recorded joint's dead-zone width exceeds e × max(tau_min,
/// 0.05 N·m) (the identification's prior on log w has sd 1): such a take-up
/// may be a concave load-deflection curve absorbed. Say when the log cannot
/// tell the two apart, with the push that would.
TakeUpProbe ProbeWideTakeUp(const io::Log& log, const std::string& log_path,
                            const models::ModelParameters& parameters,
                            const DiagnoseOptions& options, const std::vector<std::string>& names);

// --- channels ------------------------------------------------------------------
std::vector<ChannelFinding> RankChannels(const io::Log& log, const Problem& problem,
                                         const std::vector<Eigen::Vector2d>& residual,
                                         const DiagnoseOptions& options);

}  // namespace pliant::estimation::diagnosis
