// The take-up probe (docs/diagnose-method.md, "A take-up that absorbed an
// effect"). A clearance is taken up over a small load — the width the
// identification starts from is the parameters' tau_min, its prior a factor e
// either way. An identification whose log held a load-deflection curve bent
// by a missing effect (a stiffening) can read it as a clearance taken up over
// a wide load, with K low and δ wide: the diagnosis then compares only loads
// beyond that take-up and sees nothing. When a joint's take-up is that wide,
// the candidates that act on the deflection are also compared on the loads
// from twice tau_min, each with the base model's K scale, δ and take-up width
// refitted with it, against the base model's own take-up refitted alone.
#include <algorithm>
#include <cmath>
#include <cstdio>

#include "diagnosis_internal.h"

namespace pliant::estimation::diagnosis {
namespace {

std::string Format(const char* format, double a, double b) {
  char text[96];
  std::snprintf(text, sizeof text, format, a, b);
  return text;
}

// Predicted deflection (rad) of joint j with `terms` at load `load_nm` on that
// joint alone, at the typical sample's depth.
double Deflection(const Sample& typical, const BaseModel& model, const std::vector<Term>& terms,
                  int j, double load_nm) {
  Sample s = typical;
  s.state.external_torque_nm.setZero();
  s.state.external_torque_nm[j] = load_nm;
  s.state.velocity_rad_s.setZero();
  s.state.effort_rate_nm_s.setZero();
  s.state.encoder_angle_rad.setZero();
  s.reference_rad.setZero();
  std::vector<const double*> values;
  for (const Term& t : terms) values.push_back(t.parameters.data());
  return -ModelResidual<double>(s, model, terms, values)[j];
}

// The push that separates the two fitted explanations: from the largest load
// the log compares on a joint, the smallest load (up to the effort limit)
// where their predicted deflections part by more than twice a sample's noise.
std::string SeparatingPush(const Problem& problem, const BaseModel& model,
                           const std::vector<Term>& take_up, const std::vector<Term>& effect,
                           const std::string& name, double limit_nm) {
  const Sample& typical = problem.samples[problem.samples.size() / 2];
  std::string best;
  double best_load = 1e300;
  for (int j = 0; j < 2; ++j) {
    double reached = 0.0;
    for (const Sample& s : problem.samples)
      if (s.used[j]) reached = std::max(reached, std::abs(s.state.external_torque_nm[j]));
    if (reached <= 0.0) continue;
    auto gap = [&](double load) {
      return Deflection(typical, model, effect, j, load) - Deflection(typical, model, take_up, j, load);
    };
    const double at_reached = gap(reached);
    const double noise = 2.0 * problem.noise_sd_rad[j];
    for (double load = reached; load <= limit_nm; load += 0.05) {
      const double part = gap(load) - at_reached;
      if (std::abs(part) <= noise || load >= best_load) continue;
      best_load = load;
      best = "push joint " + std::to_string(j + 1) + Format(" to %.2f N·m (the log reaches %.2f N·m)", load, reached) +
             ": there the wide take-up and " + name + " predict deflections " +
             Format("%.2f mrad apart, twice the %.2f mrad noise of a sample", 1e3 * std::abs(part),
                    1e3 * problem.noise_sd_rad[j]);
      break;
    }
  }
  return best.empty() ? "no push within the effort limit separates the wide take-up from " + name
                      : best;
}

// The base model's own take-up refitted alone (K's scale and tilt, δ, the
// width), from the parameters' width and from a clearance's: the better of the
// two held out is what a candidate must beat.
struct TakeUpBaseline {
  std::vector<Term> fitted;                 ///< the refit, fitted on every row
  std::vector<Eigen::Vector2d> heldout;
  double rms_mm = 0.0;
  bool narrow = false;                      ///< the clearance's width fitted better
  double wide_rms_mm = 0.0, narrow_rms_mm = 0.0;
};

TakeUpBaseline FitBaseline(const Problem& problem, const BaseModel& model) {
  TakeUpBaseline best;
  const std::vector<bool> all(problem.groups, true);
  for (Recalibration kind : {Recalibration::kTakeUp, Recalibration::kNarrowTakeUp}) {
    const std::vector<Term> refit = {BaseRecalibrationTerm(model, kind)};
    auto heldout = CrossValidated(problem, model, {}, refit);
    const double rms = TipRmsMm(problem, heldout);
    const bool narrow = kind == Recalibration::kNarrowTakeUp;
    (narrow ? best.narrow_rms_mm : best.wide_rms_mm) = rms;
    if (narrow && rms >= best.rms_mm) continue;
    best.fitted = refit;
    best.fitted.front().parameters =
        FitTerms(problem, model, {}, refit, all, false, 1.0).parameters.front();
    best.heldout = std::move(heldout);
    best.rms_mm = rms, best.narrow = narrow;
  }
  return best;
}

std::string Describe(const BaseModel& model, const models::ModelParameters& parameters,
                     const DiagnoseOptions& options, const TakeUpBaseline& base) {
  const auto& j1 = parameters.joints[0];
  const auto& j2 = parameters.joints[1];
  const auto& fitted = base.fitted.front().parameters;
  return "the parameters take the clearance up over " +
         Format("%.3g / %.3g N·m", model.clearance_load_nm(0), model.clearance_load_nm(1)) +
         " on joint 1 / 2, beyond e × tau_min (" +
         Format("%.3g / %.3g N·m", j1.tau_min_nm, j2.tau_min_nm) +
         ", the clearance's take-up an identification starts from), with δ " +
         Format("%.1f / %.1f mrad", 1e3 * j1.backlash_rad, 1e3 * j2.backlash_rad) +
         ": a load-deflection curve bent by a missing effect reads so. Compared also from " +
         Format("%.3g / %.3g N·m", options.min_load_factor * model.compared_load_nm(0),
                options.min_load_factor * model.compared_load_nm(1)) +
         ", the model's own take-up refitted there leaves " +
         Format("%.3f mm held out (%.3f mm", base.wide_rms_mm, base.narrow_rms_mm) +
         " refitted from the clearance's take-up; the better: width " +
         Format("%.3g / %.3g N·m", model.clearance_load_nm(0) * std::exp(fitted[6]),
                model.clearance_load_nm(1) * std::exp(fitted[7])) +
         ", δ " +
         Format("%.1f / %.1f mrad)", 1e3 * (j1.backlash_rad + fitted[2]),
                1e3 * (j2.backlash_rad + fitted[3]));
}

// What the best candidate does against the baseline, in words.
std::string Verdict(const Problem& problem, const BaseModel& model, const TakeUpBaseline& base,
                    const CandidateFit& best, const DiagnoseOptions& options) {
  const auto& f = best.finding;
  std::string text = "; " + f.name + ", with the take-up refitted from the clearance's, leaves " +
                     Format("%.3f mm (%.0f %% less", f.heldout_rms_after_mm, 100.0 * f.score) +
                     Format(", p %.2g)%.0s", f.p_value, 0.0);
  if (f.missing) return text + ": the take-up is " + f.name + " absorbed, and it is called missing";
  if (f.score < options.min_unique_reduction)
    return text + ": no candidate adds to the take-up as refitted";
  std::vector<Term> effect = best.refit;
  effect.push_back(best.term);
  return text + ": this log cannot tell the take-up as refitted from " + f.name + "; " +
         SeparatingPush(problem, model, base.fitted, effect, f.name, options.filter.effort_limit_nm);
}

}  // namespace

std::array<bool, 2> Recorded(const io::Log& log) {
  return {log.header.JointRecorded(1), log.header.JointRecorded(2)};
}

bool CompareInsideWideTakeUp(std::array<bool, 2> recorded, BaseModel* model) {
  bool wide = false;
  for (int j = 0; j < 2; ++j) {
    const auto& joint = model->parameters().joints[j];
    // No clearance (δ identified 0, as on the real joint 2 clamps), or a
    // joint the log does not record: no take-up to look into.
    if (!(joint.backlash_rad > 0.0) || !recorded[j]) continue;
    const double narrow = NarrowTakeUpNm(joint);
    wide = wide || model->clearance_load_nm(j) > kWideTakeUpFactor * narrow;
  }
  for (int j = 0; j < 2 && wide; ++j) {
    const auto& joint = model->parameters().joints[j];
    if (!(joint.backlash_rad > 0.0) || !recorded[j]) continue;
    const double narrow = NarrowTakeUpNm(joint);
    if (model->clearance_load_nm(j) > narrow) model->set_compared_load_nm(j, narrow);
  }
  return wide;
}

bool RefitTakeUpWithAdded(std::array<bool, 2> recorded, const std::vector<Term>& added,
                          BaseModel* model) {
  const bool deflection = std::any_of(added.begin(), added.end(), [](const Term& t) {
    return t.effect->Info().channel == models::Channel::kDeflection;
  });
  return deflection && CompareInsideWideTakeUp(recorded, model);
}

bool FitAddedWithTheTakeUp(const BaseModel& model, Problem* problem) {
  if (problem->added_refit.empty()) return false;  // no recalibration asked for
  problem->added_refit = {BaseRecalibrationTerm(model, Recalibration::kNarrowTakeUp)};
  problem->notes.push_back(
      "the parameters' take-up is wide: the added effects are fitted with it refitted from a "
      "clearance's (K's scale and tilt, δ, the width), on the loads from twice the clearance's "
      "take-up");
  return true;
}

TakeUpProbe ProbeWideTakeUp(const io::Log& log, const std::string& log_path,
                            const models::ModelParameters& parameters,
                            const DiagnoseOptions& options, const std::vector<std::string>& names) {
  TakeUpProbe probe;
  BaseModel model(parameters);
  if (!CompareInsideWideTakeUp(Recorded(log), &model)) return probe;
  Problem problem = BuildProblem(log, log_path, model, {}, options);
  const TakeUpBaseline base = FitBaseline(problem, model);
  const auto baseline_residual = Residuals(problem, model, base.fitted);
  // Each candidate explains the curve with a clearance's take-up.
  problem.refit = {BaseRecalibrationTerm(model, Recalibration::kNarrowTakeUp)};
  for (const auto& name : names) {
    const Term candidate = MakeTerm(name);
    if (candidate.parameters.empty() ||
        candidate.effect->Info().channel != models::Channel::kDeflection)
      continue;  // an effort-side effect is not what a take-up absorbs
    probe.candidates.push_back(EvaluateCandidate(problem, model, {}, candidate, baseline_residual,
                                                 base.heldout, base.rms_mm));
  }
  std::vector<double> p;
  for (const auto& c : probe.candidates) p.push_back(c.finding.p_value);
  HolmAdjust(p);
  for (std::size_t i = 0; i < p.size(); ++i) {
    EffectFinding& f = probe.candidates[i].finding;
    f.p_value = p[i];
    f.missing = f.p_value < options.family_significance && f.score >= options.min_heldout_reduction;
    f.unique_score = f.score;  // the probe compares each with the take-up alone, not in pairs
  }
  std::stable_sort(probe.candidates.begin(), probe.candidates.end(),
                   [](const auto& a, const auto& b) { return a.finding.score > b.finding.score; });
  std::string note = Describe(model, parameters, options, base);
  if (!probe.candidates.empty())
    note += Verdict(problem, model, base, probe.candidates.front(), options);
  for (std::size_t i = 1; i < probe.candidates.size(); ++i) {
    const auto& f = probe.candidates[i].finding;
    note += (i == 1 ? "; the others: " : ", ") + f.name +
            Format(" %.0f %% (p %.2g)", 100.0 * f.score, f.p_value);
  }
  probe.notes.push_back(note);
  return probe;
}

}  // namespace pliant::estimation::diagnosis
