// Diagnose(): compare, find where the model fails, fit every candidate effect
// and rank them (docs/diagnose-method.md).
#include "pliant/estimation/diagnosis.h"

#include <algorithm>
#include <cmath>
#include <iterator>
#include <set>

#include "clustered_sandwich.h"
#include "diagnosis_internal.h"
#include "diagnosis_summary.h"
#include "pliant/estimation/free_motion_fit.h"
#include "pliant/estimation/jacobian_check.h"
#include "pliant/io/input_error.h"

namespace pliant::estimation {
namespace {

using diagnosis::Problem;
using diagnosis::Term;
using Residual = std::vector<Eigen::Vector2d>;

}  // namespace

namespace diagnosis {

CandidateFit EvaluateCandidate(const Problem& problem, const BaseModel& model,
                               const std::vector<Term>& fixed, const Term& candidate,
                               const Residual& before, const Residual& heldout_before,
                               double rms_before_mm) {
  // `before`: the residual of the baseline (the fixed terms and the refit
  // alone, fitted on every row), which the size is measured from.
  EffectFinding f;
  f.name = candidate.name;
  f.description = std::string(candidate.effect->Info().explanation);
  f.size_unit = "mm";
  const Residual heldout =
      diagnosis::CrossValidated(problem, model, fixed, diagnosis::WithRefit(problem, {candidate}));
  f.heldout_rms_before_mm = rms_before_mm;
  f.heldout_rms_after_mm = diagnosis::TipRmsMm(problem, heldout);
  f.score = rms_before_mm > 0.0 ? 1.0 - f.heldout_rms_after_mm / rms_before_mm : 0.0;
  // Rows within a segment are correlated; the held-out segments are the sample.
  f.p_value = diagnosis::BlockImprovementTest(
                  diagnosis::GainPerGroup(problem, heldout_before, heldout))
                  .p_value;

  // In-sample fit for the information criteria, the parameters and the size.
  const std::vector<bool> all(problem.groups, true);
  const auto fit = diagnosis::FitTerms(problem, model, fixed,
                                       diagnosis::WithRefit(problem, {candidate}), all, true, 1.0, true);
  std::vector<Term> with = fixed;  // the fixed terms and the refit as fitted with it
  std::vector<Term> refit = problem.refit;
  for (std::size_t t = 0; t < refit.size(); ++t) refit[t].parameters = fit.parameters[t];
  with.insert(with.end(), refit.begin(), refit.end());
  const std::vector<Term> base = with;
  Term fitted = candidate;
  fitted.parameters = fit.parameters.back();
  with.push_back(fitted);
  const diagnosis::Standardised z0 = diagnosis::Standardise(problem, before);
  const diagnosis::Standardised z1 = diagnosis::Standardise(problem, diagnosis::Residuals(problem, model, with));
  // Effective size from the residual left with the effect in: under the null
  // it is what the noise is; a wrong candidate leaves it correlated.
  const double factor = diagnosis::EffectiveSizeFactor(z1.value, z1.run);
  const double n_eff = std::max(2.0, factor * double(z1.value.size()));
  const double k = double(candidate.parameters.size());
  const double rss0 = diagnosis::SumOfSquares(z0.value), rss1 = std::max(1e-300, diagnosis::SumOfSquares(z1.value));
  const double log_ratio = std::log(rss1 / std::max(rss0, 1e-300));
  f.delta_aic = n_eff * log_ratio + 2.0 * k;
  f.delta_bic = n_eff * log_ratio + k * std::log(n_eff);

  f.parameters = fitted.parameters;
  for (const auto& spec : candidate.effect->Parameters()) f.parameter_names.push_back(spec.name);
  // The segments' jackknife, never below the white covariance scaled by the
  // residual's effective size: both count correlated rows once.
  const Eigen::Index m = Eigen::Index(candidate.parameters.size());
  const Eigen::MatrixXd covariance =
      fit.covariance.rows() >= m
          ? detail::NotBelow(fit.covariance.bottomRightCorner(m, m),
                             fit.white_covariance.bottomRightCorner(m, m) / factor)
          : Eigen::MatrixXd::Zero(m, m);
  for (Eigen::Index k = 0; k < m; ++k) f.parameter_sd.push_back(std::sqrt(std::max(0.0, covariance(k, k))));
  // Size: what the candidate (with the refit as fitted with it) changes in the
  // baseline's residual; its σ from the candidate's own parameters.
  const auto size = diagnosis::ContributionSizeMm(problem, model, base, fitted, covariance);
  f.size = diagnosis::RmsDifferenceMm(problem, before, diagnosis::Residuals(problem, model, with));
  f.size_sd = size[0] > 0.0 ? size[1] : 0.0;
  return {f, fitted, refit};
}

}  // namespace diagnosis

namespace {

// A caution for a channel whose lag or nature can mislead a reader.
std::string ChannelRemark(const ChannelFinding& c, int max_lag) {
  if (c.name == "t")
    return "the log's time: a slow drift of the residual, or any effect that changes over the "
           "session; not a cause by itself";
  if (c.name == "segment")
    return "the segment number: the residual differs between segments (depth, direction, load), "
           "not along this number";
  if (max_lag > 0 && std::abs(c.lag) >= max_lag)
    return "the best lag is at the edge of the ±" + std::to_string(max_lag) +
           " sample window: the true lag may be longer (try a larger --max-lag)";
  return "";
}

// The probe compares the deflection candidates on the rows compared here and
// on the loads inside the take-up, against the base with its take-up refitted:
// its verdict on them replaces the one that took the wide take-up as right
// (their terms here are kept, for the residual series). Those it calls
// missing come first.
void TakeProbeFindings(const diagnosis::TakeUpProbe& probe,
                       std::vector<diagnosis::CandidateFit>& candidates,
                       std::vector<std::string>* selected) {
  std::vector<diagnosis::CandidateFit> found, rest;
  for (auto& c : candidates) {
    const auto it = std::find_if(probe.candidates.begin(), probe.candidates.end(),
                                 [&](const auto& p) { return p.finding.name == c.finding.name; });
    if (it != probe.candidates.end()) {
      c.finding = it->finding;
      c.scored_on_probe_rows = true;
      c.finding.description += " (compared on the loads inside the parameters' wide take-up, "
                               "with the take-up refitted: see the notes)";
      selected->erase(std::remove(selected->begin(), selected->end(), c.finding.name),
                      selected->end());
    }
    (it != probe.candidates.end() && c.finding.missing ? found : rest).push_back(std::move(c));
  }
  std::stable_sort(found.begin(), found.end(),
                   [](const auto& a, const auto& b) { return a.finding.score > b.finding.score; });
  std::stable_partition(rest.begin(), rest.end(), [](const auto& c) { return c.finding.missing; });
  for (auto it = found.rbegin(); it != found.rend(); ++it)
    selected->insert(selected->begin(), it->finding.name);
  candidates = std::move(found);
  candidates.insert(candidates.end(), std::make_move_iterator(rest.begin()),
                    std::make_move_iterator(rest.end()));
}

}  // namespace

std::vector<std::string> CandidateEffectNames() {
  static const std::set<std::string> kBaseModel = {"bias_torque",       "compliance",
                                                   "backlash_sign",     "backlash_deadzone",
                                                   "backlash_hysteresis", "bias_torque_fourier"};
  // The arm's inertia is fitted from free motion (ReadsOnlyTheAcceleration).
  std::vector<std::string> names;
  for (const auto& name : EffectCatalogue::Global().Names()) {
    if (!kBaseModel.count(name) && !ReadsOnlyTheAcceleration(name)) names.push_back(name);
  }
  return names;
}

// Unknown names, an effect added twice, or added and a candidate at once.
void CheckEffectOptions(const DiagnoseOptions& options, const std::string& log_path) {
  auto known = [&](const std::string& name) {
    if (EffectCatalogue::Global().Contains(name)) return;
    std::string list;
    for (const auto& n : CandidateEffectNames()) list += (list.empty() ? "" : ", ") + n;
    throw io::InputError(log_path, 0, 0, "no effect named '" + name + "'", "use one of: " + list);
  };
  std::set<std::string> seen;
  for (const auto& name : options.added_effects) {
    known(name);
    if (!seen.insert(name).second) {
      throw io::InputError("--add", 0, 0, "effect '" + name + "' is given twice",
                           "give each effect once: it is fitted once");
    }
  }
  std::set<std::string> candidates;
  for (const auto& name : options.candidates) {
    known(name);
    if (seen.count(name)) {
      throw io::InputError("--candidate", 0, 0,
                           "effect '" + name + "' is both added (--add) and a candidate",
                           "an added effect is part of the model; drop it from --candidate");
    }
    if (!candidates.insert(name).second) {
      throw io::InputError("--candidate", 0, 0, "effect '" + name + "' is given twice",
                           "give each candidate once");
    }
  }
}

Diagnosis Diagnose(const io::Log& log, const std::string& log_path,
                   const models::ModelParameters& parameters, const DiagnoseOptions& options) {
  const std::string why = models::ValidateParameters(parameters);
  if (!why.empty()) {
    throw io::InputError("parameters", 0, 0, why, "give parameters that pass `pliant check`");
  }
  CheckEffectOptions(options, log_path);
  std::vector<Term> added;
  for (const auto& name : options.added_effects) added.push_back(diagnosis::MakeTerm(name));
  std::vector<std::string> names = options.candidates.empty() ? CandidateEffectNames() : options.candidates;

  // The file's own effects are part of the model compared (an --add fits one again).
  diagnosis::BaseModel model(parameters, options.added_effects);
  // An added deflection effect on a wide take-up is fitted as the probe
  // compares candidates: from the clearance's take-up on, with it refitted.
  const bool take_up = options.probe_wide_take_up &&
                       diagnosis::RefitTakeUpWithAdded(diagnosis::Recorded(log), added, &model);
  Problem problem = diagnosis::BuildProblem(log, log_path, model, added, options);
  for (const Term& t : model.file_effects()) {
    problem.notes.push_back("the parameters hold " + t.name +
                            ": it is part of the model compared, not a candidate");
  }
  diagnosis::NoteFittedOnThisLog(parameters, log_path, &problem.notes);
  diagnosis::SetRecalibration(model, options.recalibrate_base, &problem);
  if (take_up) diagnosis::FitAddedWithTheTakeUp(model, &problem);
  const std::vector<bool> all(problem.groups, true);
  Diagnosis d;
  d.reference = problem.reference;
  d.added_effects = options.added_effects;
  d.notes = problem.notes;
  d.joint_recorded[0] = problem.joint_recorded[0], d.joint_recorded[1] = problem.joint_recorded[1];
  d.max_lag_samples = options.max_lag_samples;

  const Residual before = diagnosis::Residuals(problem, model, {});
  const Residual heldout_before = diagnosis::CrossValidated(problem, model, {}, {});
  d.rms_before_mm = diagnosis::TipRmsMm(problem, heldout_before);
  std::vector<Term> fixed;
  Residual after = before;
  Residual heldout_baseline;
  if (!added.empty()) {
    const auto fitted = diagnosis::FitAdded(problem, model, added, &fixed);
    d.added = fitted.effects;
    d.recalibration = fitted.recalibration;
    d.added_covariance = fitted.covariance;
    d.rms_after_mm = diagnosis::TipRmsMm(
        problem,
        diagnosis::CrossValidated(problem, model, {}, diagnosis::WithAddedRefit(problem, added)));
    after = diagnosis::Residuals(problem, model, fixed);
    // The recalibration as fitted with them (K's depth tilt included, which
    // the candidates' refit lacks) stays in the model the candidates extend.
    if (fitted.recalibration) {
      fixed.push_back(problem.added_refit.front());
      fixed.back().parameters = fitted.recalibration->parameters;
    }
  }
  const Residual baseline = added.empty() ? before : after;
  // Candidates are tried on top of the added effects as fitted, each against
  // the baseline of the recalibrated model.
  heldout_baseline = diagnosis::CrossValidated(problem, model, fixed, problem.refit);
  const double baseline_rms = diagnosis::TipRmsMm(problem, heldout_baseline);
  d.rms_recalibrated_mm = baseline_rms;
  Residual recalibrated = baseline;
  if (!problem.refit.empty()) {
    const auto fit = diagnosis::FitTerms(problem, model, fixed, problem.refit, all, false, 1.0);
    std::vector<Term> with = fixed;
    for (std::size_t t = 0; t < problem.refit.size(); ++t) {
      with.push_back(problem.refit[t]);
      with.back().parameters = fit.parameters[t];
    }
    recalibrated = diagnosis::Residuals(problem, model, with);
  }

  std::vector<diagnosis::CandidateFit> candidates;
  for (const auto& name : names) {
    const auto& a = options.added_effects;
    if (std::find(a.begin(), a.end(), name) != a.end()) continue;  // already in the model
    const auto& held = model.file_effects();
    if (std::any_of(held.begin(), held.end(), [&](const Term& t) { return t.name == name; }))
      continue;
    const Term candidate = diagnosis::MakeTerm(name);
    if (candidate.parameters.empty()) continue;  // nothing to fit: no size, no test
    // A quasi-static log's t is a pose index: what changes in time is not read
    // from it (its note says so).
    const auto channels = diagnosis::ChannelsOf(*candidate.effect);
    if (problem.quasi_static && std::count(channels.begin(), channels.end(), "t")) continue;
    auto c =
        diagnosis::EvaluateCandidate(problem, model, fixed, candidate, recalibrated,
                                     heldout_baseline, baseline_rms);
    c.finding.channels = channels;
    candidates.push_back(std::move(c));
  }
  std::vector<double> p;
  for (const auto& c : candidates) p.push_back(c.finding.p_value);
  diagnosis::HolmAdjust(p);
  for (std::size_t i = 0; i < p.size(); ++i) {
    EffectFinding& f = candidates[i].finding;
    f.p_value = p[i];
    f.missing = f.p_value < options.family_significance && f.score >= options.min_heldout_reduction;
  }
  d.selected = diagnosis::RankBySeparation(problem, model, fixed, options, candidates);
  if (added.empty() && options.probe_wide_take_up) {
    auto probe = diagnosis::ProbeWideTakeUp(log, log_path, parameters, options, names);
    d.notes.insert(d.notes.end(), probe.notes.begin(), probe.notes.end());
    TakeProbeFindings(probe, candidates, &d.selected);
  }
  for (const auto& c : candidates) d.effects.push_back(c.finding);
  for (const auto& f : d.effects) {
    if (f.missing) {
      d.missing_effect = f.name;
      break;
    }
  }
  if (added.empty() && !candidates.empty()) {
    const auto& best = candidates.front();
    // A take-up probe's finding is scored on other rows: held out on these.
    d.rms_after_mm = !best.scored_on_probe_rows
                         ? best.finding.heldout_rms_after_mm
                         : diagnosis::TipRmsMm(problem, diagnosis::CrossValidated(
                                                            problem, model, fixed,
                                                            diagnosis::WithRefit(problem, {best.term})));
    std::vector<Term> with = best.refit;
    with.push_back(best.term);
    after = diagnosis::Residuals(problem, model, with);
  } else if (added.empty()) {
    d.rms_after_mm = d.rms_before_mm;
  }

  // The noise is the same in both; the model's error, which the floor also
  // reads where it changes fast, is smaller in one.
  d.noise_floor_mm = std::min(diagnosis::NoiseFloorMm(problem, heldout_before),
                              diagnosis::NoiseFloorMm(problem, after));
  d.before = diagnosis::Summarise(problem, before, options);
  d.after = diagnosis::Summarise(problem, after, options);
  if (problem.joint_recorded[0] && problem.joint_recorded[1]) {
    diagnosis::AddFilterNis(log, parameters, options, problem, d.before);
  } else {
    d.notes.push_back("the filter's NIS is not computed: it needs both joints recorded");
  }
  d.after.mean_nis = d.before.mean_nis;  // the filter has no candidate effect in it
  d.after.nis_band[0] = d.before.nis_band[0], d.after.nis_band[1] = d.before.nis_band[1];
  d.channels = diagnosis::RankChannels(log, problem, baseline, options);
  for (auto& c : d.channels) c.remark = ChannelRemark(c, options.max_lag_samples);

  for (std::size_t i = 0; i < problem.samples.size(); ++i) {
    const auto& s = problem.samples[i];
    d.series.row.push_back(s.row);
    for (int j = 0; j < 2; ++j) {
      d.series.residual_before_rad[j].push_back(s.used[j] ? before[i][j] : NAN);
      d.series.residual_after_rad[j].push_back(s.used[j] ? after[i][j] : NAN);
    }
    const int j = s.used[0] ? 0 : 1;
    d.series.standardised_innovation.push_back(before[i][j] / problem.noise_sd_rad[j]);
  }
  return d;
}

}  // namespace pliant::estimation
