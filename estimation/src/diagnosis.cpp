// Diagnose(): compare, find where the model fails, fit every candidate effect
// and rank them (docs/diagnose-method.md).
#include "pliant/estimation/diagnosis.h"

#include <algorithm>
#include <cmath>
#include <set>

#include "diagnosis_internal.h"
#include "pliant/estimation/filter_log.h"
#include "pliant/estimation/jacobian_check.h"
#include "pliant/io/input_error.h"

namespace pliant::estimation {
namespace {

using diagnosis::Problem;
using diagnosis::Term;
using Residual = std::vector<Eigen::Vector2d>;

Term MakeTerm(const std::string& name) {
  std::shared_ptr<const EffectModel> effect = EffectCatalogue::Global().Create(name);
  return {effect, effect->DefaultParameters(), name};
}

// Standardised residual entries of the used joints, joint 1's run then joint 2's.
struct Standardised {
  std::vector<double> value;
  std::vector<int> run;
};
Standardised Standardise(const Problem& problem, const Residual& r) {
  Standardised out;
  for (int j = 0; j < 2; ++j) {
    for (std::size_t i = 0; i < r.size(); ++i) {
      if (!problem.samples[i].used[j]) continue;
      out.value.push_back(r[i][j] / problem.noise_sd_rad[j]);
      out.run.push_back(2 * problem.samples[i].group + j);
    }
  }
  return out;
}

double SumOfSquares(const std::vector<double>& x) {
  double s = 0.0;
  for (double v : x) s += v * v;
  return s;
}

// Held-out residual: each fold's samples under parameters fitted on the
// others (none fitted: the model as it is, profiled the same way, so that
// before and after are compared alike).
Residual CrossValidated(const Problem& problem, const diagnosis::BaseModel& model,
                        const std::vector<Term>& fixed, const std::vector<Term>& fitted) {
  Residual heldout(problem.samples.size(), Eigen::Vector2d::Zero());
  for (int fold = 0; fold < problem.folds; ++fold) {
    std::vector<bool> train(problem.groups);
    for (int g = 0; g < problem.groups; ++g) train[g] = problem.fold_of_group[g] != fold;
    std::vector<Term> terms = fixed;
    if (!fitted.empty()) {
      const auto fit = diagnosis::FitTerms(problem, model, fixed, fitted, train, false, 1.0);
      for (std::size_t t = 0; t < fitted.size(); ++t) {
        terms.push_back(fitted[t]);
        terms.back().parameters = fit.parameters[t];
      }
    }
    std::vector<bool> test(problem.groups);
    for (int g = 0; g < problem.groups; ++g) test[g] = !train[g];
    // The held-out tip angle is profiled on the held-out samples alone.
    const Residual r = diagnosis::Residuals(problem, model, terms, &test);
    for (std::size_t i = 0; i < r.size(); ++i) {
      if (problem.fold_of_group[problem.samples[i].group] == fold) heldout[i] = r[i];
    }
  }
  return heldout;
}

ResidualStatistics Statistics(const Problem& problem, const Residual& r, const DiagnoseOptions& o) {
  ResidualStatistics s;
  s.samples = r.size();
  s.rms_mm = diagnosis::TipRmsMm(problem, r);
  for (int j = 0; j < 2; ++j) {
    double sum = 0.0, square = 0.0, n = 0.0;
    for (std::size_t i = 0; i < r.size(); ++i) {
      if (!problem.samples[i].used[j]) continue;
      sum += r[i][j], square += r[i][j] * r[i][j], n += 1.0;
    }
    s.bias_rad[j] = n > 0.0 ? sum / n : 0.0;
    s.rms_rad[j] = n > 0.0 ? std::sqrt(square / n) : 0.0;
  }
  const Standardised z = Standardise(problem, r);
  const auto lb = diagnosis::LjungBox(z.value, o.ljung_box_lags);
  const auto jb = diagnosis::JarqueBera(z.value);
  s.ljung_box_q = lb.statistic, s.ljung_box_p = lb.p_value;
  s.normality_statistic = jb.statistic, s.normality_p = jb.p_value;
  return s;
}

// The filter's NIS over the compared rows (it runs over every row in order).
void AddFilterNis(const io::Log& log, const models::ModelParameters& parameters,
                  const DiagnoseOptions& options, const Problem& problem, ResidualStatistics& s) {
  ComplianceFilter filter(parameters, options.filter);
  const io::StandardColumns columns(log.header);
  std::vector<bool> compared(log.Rows(), false);
  for (const auto& sample : problem.samples) compared[sample.row] = true;
  double nis = 0.0, dof = 0.0;
  for (std::size_t r = 0; r < log.Rows(); ++r) {
    const FilterEstimate e = filter.Step(SampleFromRow(columns, &log.values[r * log.Columns()]));
    if (compared[r] && e.nis_dof > 0) nis += e.nis, dof += e.nis_dof;
  }
  s.mean_nis = dof > 0.0 ? nis / dof : 0.0;
  const auto band = diagnosis::ChiSquaredMeanBand(dof);
  s.nis_band[0] = band[0], s.nis_band[1] = band[1];
}

EffectFinding Evaluate(const Problem& problem, const diagnosis::BaseModel& model,
                       const std::vector<Term>& fixed, const Term& candidate,
                       const Residual& before, double rms_before_mm) {
  EffectFinding f;
  f.name = candidate.name;
  f.description = std::string(candidate.effect->Info().explanation);
  f.size_unit = "mm";
  const Residual heldout = CrossValidated(problem, model, fixed, {candidate});
  f.heldout_rms_before_mm = rms_before_mm;
  f.heldout_rms_after_mm = diagnosis::TipRmsMm(problem, heldout);
  f.score = rms_before_mm > 0.0 ? 1.0 - f.heldout_rms_after_mm / rms_before_mm : 0.0;

  // In-sample fit for the test, the information criteria and the size.
  const std::vector<bool> all(problem.groups, true);
  Term fitted = candidate;
  const auto fit = diagnosis::FitTerms(problem, model, fixed, {candidate}, all, true, 1.0);
  fitted.parameters = fit.parameters[0];
  std::vector<Term> with = fixed;
  with.push_back(fitted);
  const Standardised z0 = Standardise(problem, before);
  const Standardised z1 = Standardise(problem, diagnosis::Residuals(problem, model, with));
  // Effective size from the residual left with the effect in: under the null
  // it is what the noise is; a wrong candidate leaves it correlated.
  const double factor = diagnosis::EffectiveSizeFactor(z1.value, z1.run);
  const double n_eff = std::max(2.0, factor * double(z1.value.size()));
  const double k = double(candidate.parameters.size());
  const double rss0 = SumOfSquares(z0.value), rss1 = std::max(1e-300, SumOfSquares(z1.value));
  const double log_ratio = std::log(rss1 / std::max(rss0, 1e-300));
  f.delta_aic = n_eff * log_ratio + 2.0 * k;
  f.delta_bic = n_eff * log_ratio + k * std::log(n_eff);
  const double d2 = std::max(1.0, n_eff - k);
  f.p_value = diagnosis::FUpperTail((rss0 - rss1) / k / (rss1 / d2), k, d2);

  f.parameters = fitted.parameters;
  for (double sd : fit.parameter_sd[0]) f.parameter_sd.push_back(sd / std::sqrt(factor));
  for (const auto& spec : candidate.effect->Parameters()) f.parameter_names.push_back(spec.name);
  const auto size =
      diagnosis::ContributionSizeMm(problem, model, fixed, fitted, fit.covariance / factor);
  f.size = size[0], f.size_sd = size[1];
  return f;
}

// The log channels an effect reads: the inputs of the joint state its
// contribution has a derivative with respect to (parameters moved one prior
// sd off their defaults, at a light and a heavy load), in the log's names.
std::vector<std::string> ChannelsOf(const EffectModel& effect) {
  static const char* kLogName[models::kJointStateSize] = {
      "q1", "q2", "q3", "tau1", "tau2", "v1", "v2", "t", "dtau1/dt", "dtau2/dt",
      "travel1", "travel2"};
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
    const auto check = CheckEffectJacobians(effect, parameters, state);
    for (int k = 0; k < models::kJointStateSize; ++k)
      used[k] = used[k] || check.autodiff.col(Eigen::Index(parameters.size()) + k).cwiseAbs().maxCoeff() > 0.0;
  }
  std::vector<std::string> channels;
  for (int k = 0; k < models::kJointStateSize; ++k) {
    if (used[k]) channels.push_back(kLogName[k]);
  }
  return channels;
}

}  // namespace

std::vector<std::string> CandidateEffectNames() {
  static const std::set<std::string> kBaseModel = {"bias_torque",       "compliance",
                                                   "backlash_sign",     "backlash_deadzone",
                                                   "backlash_hysteresis", "bias_torque_fourier"};
  std::vector<std::string> names;
  for (const auto& name : EffectCatalogue::Global().Names()) {
    if (!kBaseModel.count(name)) names.push_back(name);
  }
  return names;
}

Diagnosis Diagnose(const io::Log& log, const std::string& log_path,
                   const models::ModelParameters& parameters, const DiagnoseOptions& options) {
  const std::string why = models::ValidateParameters(parameters);
  if (!why.empty()) {
    throw io::InputError("parameters", 0, 0, why, "give parameters that pass `pliant check`");
  }
  auto known = [&](const std::string& name) {
    if (EffectCatalogue::Global().Contains(name)) return;
    std::string list;
    for (const auto& n : CandidateEffectNames()) list += (list.empty() ? "" : ", ") + n;
    throw io::InputError(log_path, 0, 0, "no effect named '" + name + "'", "use one of: " + list);
  };
  std::vector<Term> added;
  for (const auto& name : options.added_effects) known(name), added.push_back(MakeTerm(name));
  std::vector<std::string> names = options.candidates.empty() ? CandidateEffectNames() : options.candidates;
  for (const auto& name : names) known(name);

  const diagnosis::BaseModel model(parameters);
  const Problem problem = diagnosis::BuildProblem(log, log_path, model, added, options);
  const std::vector<bool> all(problem.groups, true);
  Diagnosis d;
  d.reference = problem.reference;
  d.added_effects = options.added_effects;

  const Residual before = diagnosis::Residuals(problem, model, {});
  d.rms_before_mm = diagnosis::TipRmsMm(problem, CrossValidated(problem, model, {}, {}));
  std::vector<Term> fixed;
  Residual after = before;
  if (!added.empty()) {
    const auto fit = diagnosis::FitTerms(problem, model, {}, added, all, false, 1.0);
    fixed = added;
    for (std::size_t t = 0; t < added.size(); ++t) fixed[t].parameters = fit.parameters[t];
    d.rms_after_mm = diagnosis::TipRmsMm(problem, CrossValidated(problem, model, {}, added));
    after = diagnosis::Residuals(problem, model, fixed);
  }
  const Residual baseline = fixed.empty() ? before : after;
  const double baseline_rms =
      fixed.empty() ? d.rms_before_mm : diagnosis::TipRmsMm(problem, CrossValidated(problem, model, fixed, {}));

  for (const auto& name : names) {
    if (std::find(options.added_effects.begin(), options.added_effects.end(), name) !=
        options.added_effects.end())
      continue;
    const Term candidate = MakeTerm(name);
    if (candidate.parameters.empty()) continue;  // nothing to fit: no size, no test
    EffectFinding f = Evaluate(problem, model, fixed, candidate, baseline, baseline_rms);
    f.channels = ChannelsOf(*candidate.effect);
    d.effects.push_back(std::move(f));
  }
  std::vector<double> p;
  for (const auto& f : d.effects) p.push_back(f.p_value);
  diagnosis::HolmAdjust(p);
  for (std::size_t i = 0; i < p.size(); ++i) {
    EffectFinding& f = d.effects[i];
    f.p_value = p[i];
    f.missing = f.p_value < options.family_significance && f.score >= options.min_heldout_reduction;
  }
  std::stable_sort(d.effects.begin(), d.effects.end(),
                   [](const EffectFinding& a, const EffectFinding& b) { return a.score > b.score; });
  for (const auto& f : d.effects) {
    if (f.missing) {
      d.missing_effect = f.name;
      break;
    }
  }
  if (added.empty() && !d.effects.empty()) {
    const EffectFinding& best = d.effects.front();
    d.rms_after_mm = best.heldout_rms_after_mm;
    Term term = MakeTerm(best.name);
    term.parameters = best.parameters;
    after = diagnosis::Residuals(problem, model, {term});
  } else if (added.empty()) {
    d.rms_after_mm = d.rms_before_mm;
  }

  d.before = Statistics(problem, before, options);
  d.after = Statistics(problem, after, options);
  AddFilterNis(log, parameters, options, problem, d.before);
  d.after.mean_nis = d.before.mean_nis;  // the filter has no candidate effect in it
  d.after.nis_band[0] = d.before.nis_band[0], d.after.nis_band[1] = d.before.nis_band[1];
  d.channels = diagnosis::RankChannels(log, problem, baseline, options);

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
