// The catalogue effects fitted into the model, jointly with the base model's
// compliance scale and clearance: `pliant diagnose --add` on one log and
// `pliant identify --effect` on the held-tip rows of all its logs
// (pliant/estimation/effect_fit.h).
#include "pliant/estimation/effect_fit.h"

#include <algorithm>
#include <cmath>

#include "diagnosis_internal.h"
#include "pliant/estimation/identify_logs.h"
#include "pliant/estimation/jacobian_check.h"
#include "pliant/io/input_error.h"

namespace pliant::estimation {
namespace diagnosis {

Term MakeTerm(const std::string& name) {
  std::shared_ptr<const EffectModel> effect = EffectCatalogue::Global().Create(name);
  return {effect, effect->DefaultParameters(), name, {}, {}};
}

// The log channels an effect reads: the inputs of the joint state its
// contribution has a derivative with respect to (parameters moved one prior
// sd off their defaults, at a light and a heavy load), in the log's names.
std::vector<std::string> ChannelsOf(const EffectModel& effect) {
  // K(L) is no column of the log: the model's law at the row's depth.
  static const char* kLogName[models::kJointStateSize] = {
      "q1", "q2", "q3", "tau1", "tau2", "v1", "v2", "t", "dtau1/dt", "dtau2/dt",
      "travel1", "travel2", "d2q1/dt2", "d2q2/dt2", nullptr, nullptr};
  std::vector<double> parameters;
  for (const auto& spec : effect.Parameters()) {
    const double moved = spec.default_value + spec.prior_sd;
    parameters.push_back(moved <= spec.upper_bound ? moved : spec.default_value - spec.prior_sd);
  }
  std::vector<bool> used(models::kJointStateSize, false);
  for (double load : {0.04, 0.7}) {
    models::JointState<double> state;
    state.encoder_angle_rad << 0.31, -0.27;
    state.insertion_depth_m = 0.143;
    state.external_torque_nm << load, -1.3 * load;
    state.velocity_rad_s << 0.02, -0.01;
    state.time_s = 12.5;
    state.effort_rate_nm_s << 0.4, -0.7;
    state.travel_since_reversal_rad << 0.003, -0.001;
    state.acceleration_rad_s2 << 0.3, -0.2;
    state.compliance_rad_per_nm << 0.05, 0.03;
    const auto check = CheckEffectJacobians(effect, parameters, state);
    for (int k = 0; k < models::kJointStateSize; ++k)
      used[k] = used[k] || check.autodiff.col(Eigen::Index(parameters.size()) + k).cwiseAbs().maxCoeff() > 0.0;
  }
  std::vector<std::string> channels;
  for (int k = 0; k < models::kJointStateSize; ++k) {
    if (used[k] && kLogName[k] != nullptr) channels.push_back(kLogName[k]);
  }
  return channels;
}

namespace {

// A fitted term as a finding: its values, sd and names.
EffectFinding FindingOf(const Term& term, const std::vector<double>& values,
                        const std::vector<std::vector<double>>& sd, std::size_t index) {
  EffectFinding f;
  f.name = term.name;
  f.description = std::string(term.effect->Info().explanation);
  f.channels = ChannelsOf(*term.effect);
  f.parameters = values;
  f.parameter_sd = sd.size() > index ? sd[index] : std::vector<double>(values.size(), 0.0);
  for (const auto& spec : term.effect->Parameters()) f.parameter_names.push_back(spec.name);
  f.size_unit = "mm";
  return f;
}

}  // namespace

FittedEffects FitAdded(const Problem& problem, const BaseModel& model,
                       const std::vector<Term>& added, std::vector<Term>* fixed) {
  const std::vector<bool> all(problem.groups, true);
  const auto fit = FitTerms(problem, model, {}, WithAddedRefit(problem, added), all, true, 1.0, true);
  FittedEffects out;
  const std::size_t first = problem.added_refit.size();
  if (first == 1)
    out.recalibration = FindingOf(problem.added_refit[0], fit.parameters[0], fit.parameter_sd, 0);
  *fixed = added;
  for (std::size_t t = 0; t < added.size(); ++t) {
    (*fixed)[t].parameters = fit.parameters[first + t];
    out.effects.push_back(FindingOf(added[t], (*fixed)[t].parameters, fit.parameter_sd, first + t));
  }
  out.covariance = fit.covariance;
  return out;
}

namespace {

// Appends `more`'s samples, its segments and held runs numbered after
// `merged`'s: one problem over the held-tip rows of several logs.
void Append(const Problem& more, Problem* merged) {
  for (Sample s : more.samples) {
    s.group += merged->groups;
    s.tip_group += merged->tip_groups;
    merged->samples.push_back(s);
  }
  // The residual's noise scale: the logs' own, weighted by their samples.
  const double n0 = double(merged->samples.size() - more.samples.size());
  const double n1 = double(more.samples.size());
  for (int j = 0; j < 2; ++j) {
    merged->noise_sd_rad[j] = std::sqrt((n0 * std::pow(merged->noise_sd_rad[j], 2) +
                                         n1 * std::pow(more.noise_sd_rad[j], 2)) / (n0 + n1));
    merged->joint_recorded[j] = merged->joint_recorded[j] || more.joint_recorded[j];
  }
  merged->groups += more.groups;
  merged->tip_groups += more.tip_groups;
}

bool HasHeldTip(const io::Log& log) {
  const int column = log.header.Index("tip_fixed");
  if (column < 0) return false;
  for (std::size_t r = 0; r < log.Rows(); ++r) {
    if (log.Value(r, column) > 0.5) return true;
  }
  return false;
}

// An effect the held rows did not inform: every parameter's σ is still above
// its prior's/√2 (the data carried less information than the prior). The
// parameters file then holds the prior, and the filter takes its σ as doubt;
// the note names where the effect can be fitted.
std::string UninformedNote(const EffectFinding& f, const Term& term) {
  const auto specs = term.effect->Parameters();
  for (std::size_t k = 0; k < specs.size() && k < f.parameter_sd.size(); ++k) {
    if (!(f.parameter_sd[k] >= specs[k].prior_sd / std::sqrt(2.0))) return "";
  }
  return f.name + ": the held rows here do not inform it (every parameter's σ is above its "
                  "prior's/√2), so it stays near its prior and the filter takes that σ as doubt; "
                  "fit it on a log where what it reads (" + JoinedPaths(f.channels) +
         ") varies under load, e.g. `pliant diagnose --params FILE LOG --add " + f.name +
         " --write-params OUT.json`";
}

}  // namespace
}  // namespace diagnosis

LogEffectFit FitEffectsOnLogs(const std::vector<NamedLog>& logs,
                              const models::ModelParameters& parameters,
                              const std::vector<std::string>& names, DiagnoseOptions options) {
  using diagnosis::Term;
  std::vector<Term> added;
  for (const auto& name : names) added.push_back(diagnosis::MakeTerm(name));
  // The file's other effects stay in the model at their values.
  diagnosis::BaseModel model(parameters, names);
  std::array<bool, 2> recorded = {false, false};
  for (const NamedLog& named : logs) {
    if (!diagnosis::HasHeldTip(*named.log)) continue;
    for (int j = 0; j < 2; ++j) recorded[j] = recorded[j] || named.log->header.JointRecorded(j + 1);
  }
  // A deflection effect on a wide take-up is fitted as diagnose --add fits it.
  const bool take_up = options.probe_wide_take_up &&
                       diagnosis::RefitTakeUpWithAdded(recorded, added, &model);
  // The identification reads the tip only where it was held: the truth a
  // simulated log carries (q*_true) is for scoring, never for fitting.
  options.reference = "tip_fixed";
  LogEffectFit out;
  diagnosis::Problem problem;
  problem.profile_tip = true;
  problem.reference = "tip_fixed";
  problem.joint_recorded[0] = problem.joint_recorded[1] = false;
  std::vector<std::string> all_paths;
  for (const NamedLog& named : logs) {
    all_paths.push_back(named.path);
    if (!diagnosis::HasHeldTip(*named.log)) continue;
    const auto one = diagnosis::BuildProblem(*named.log, named.path, model, added, options);
    diagnosis::Append(one, &problem);
    out.logs.push_back(named.path);
    for (const auto& note : one.notes) out.notes.push_back(named.path + ": " + note);
  }
  if (out.logs.empty()) {
    throw io::InputError(JoinedPaths(all_paths), 0, 0,
                         "no log holds the tip (tip_fixed = 1), and an effect is fitted where the "
                         "tip's place is known",
                         "add a clamped-beam or divot log, or identify without --effect");
  }
  problem.rms_window_s = options.rms_window_s;
  diagnosis::AssignFolds(std::max(2, options.folds), &problem);
  diagnosis::SetRecalibration(model, options.recalibrate_base, &problem);
  if (take_up && diagnosis::FitAddedWithTheTakeUp(model, &problem))
    out.notes.push_back(problem.notes.back());
  std::vector<Term> fixed;
  out.fitted = diagnosis::FitAdded(problem, model, added, &fixed);
  for (std::size_t t = 0; t < added.size() && t < out.fitted.effects.size(); ++t) {
    const std::string note = diagnosis::UninformedNote(out.fitted.effects[t], added[t]);
    if (!note.empty()) out.notes.push_back(note);
  }
  out.samples = problem.samples.size();
  out.segments = problem.groups;
  out.rms_given_mm = diagnosis::TipRmsMm(problem, diagnosis::CrossValidated(problem, model, {}, {}));
  out.rms_refit_mm =
      diagnosis::TipRmsMm(problem, diagnosis::CrossValidated(problem, model, {}, problem.added_refit));
  out.rms_with_effects_mm = diagnosis::TipRmsMm(
      problem,
      diagnosis::CrossValidated(problem, model, {}, diagnosis::WithAddedRefit(problem, added)));
  return out;
}

}  // namespace pliant::estimation
