// pliant identify --effect (identify_effects.h).
#include "identify_effects.h"

#include <algorithm>
#include <cstdio>

#include "pliant/estimation/identification_report.h"
#include "pliant/io/input_error.h"
#include "pliant/io/progress.h"

namespace pliant::cli {
namespace {

std::vector<estimation::NamedLog> Named(const std::vector<io::Log>& logs,
                                        const std::vector<std::string>& paths) {
  std::vector<estimation::NamedLog> named;
  for (std::size_t i = 0; i < logs.size(); ++i) named.push_back({&logs[i], paths[i]});
  return named;
}

std::string ParametersText(const estimation::EffectFinding& e) {
  char line[160];
  std::string text = "    " + e.name + ":";
  for (std::size_t k = 0; k < e.parameters.size(); ++k) {
    std::snprintf(line, sizeof line, " %s = %.4g ± %.2g", e.parameter_names[k].c_str(),
                  e.parameters[k], k < e.parameter_sd.size() ? e.parameter_sd[k] : 0.0);
    text += line;
  }
  return text + "\n";
}

std::string HeldText(const estimation::LogEffectFit& fit) {
  char line[320];
  std::snprintf(line, sizeof line,
                "  effects fitted on the held tip of %s (%zu samples, %d segments), with each "
                "joint's compliance scale and clearance:\n",
                JoinedPaths(fit.logs).c_str(), fit.samples, fit.segments);
  std::string text = line;
  for (const auto& e : fit.fitted.effects) text += ParametersText(e);
  std::snprintf(line, sizeof line,
                "    held-out RMS error at the tip: %.3f mm as identified, %.3f mm with K and δ "
                "refitted, %.3f mm with the effects\n",
                fit.rms_given_mm, fit.rms_refit_mm, fit.rms_with_effects_mm);
  text += line;
  for (const auto& note : fit.notes) text += "    note: " + note + "\n";
  return text;
}

std::string FreeText(const estimation::FreeMotionFit& fit) {
  char line[320];
  std::snprintf(line, sizeof line,
                "  the arm's dynamics fitted on the free motion of %s (%zu rows; σ over %d blocks "
                "of %.1f s, the residual's correlation time %.2f s):\n",
                JoinedPaths(fit.logs).c_str(), fit.rows, fit.blocks, fit.block_s, fit.correlation_s);
  std::string text = line;
  for (const auto& e : fit.fitted.effects) text += ParametersText(e);
  std::snprintf(line, sizeof line,
                "    effort beyond the bias table, RMS: %.3f / %.3f N·m, with the effects %.3f / "
                "%.3f N·m\n",
                fit.rms_before_nm[0], fit.rms_before_nm[1], fit.rms_after_nm[0],
                fit.rms_after_nm[1]);
  text += line;
  for (const auto& note : fit.notes) text += "    note: " + note + "\n";
  return text;
}

}  // namespace

EffectFits FitEffects(const std::vector<std::string>& names, const std::vector<io::Log>& logs,
                      const std::vector<std::string>& paths,
                      estimation::IdentificationResult* result) {
  EffectFits fits;
  if (names.empty()) return fits;
  io::Progress progress("pliant identify: fitting " + JoinedPaths(names));
  const bool free_motion = std::any_of(logs.begin(), logs.end(), [](const io::Log& log) {
    return estimation::FreeMotionSeconds(log) >= 1.0;
  });
  std::vector<std::string> on_free, on_held;
  for (const auto& name : names)
    (free_motion && estimation::FittedFromFreeMotion(name) ? on_free : on_held).push_back(name);
  const auto named = Named(logs, paths);
  // The dynamics first: the held-tip fit then keeps them in its model.
  if (!on_free.empty()) {
    fits.free_motion = estimation::FitEffectsOnFreeMotion(named, result->parameters, on_free);
    result->parameters = estimation::WithFittedEffects(
        result->parameters, fits.free_motion->fitted,
        "pliant identify on the free motion of " + JoinedPaths(fits.free_motion->logs));
  }
  // An effect the diagnosis does not fit on a held tip has nowhere else to go.
  const auto held_fittable = estimation::CandidateEffectNames();
  for (const auto& name : on_held) {
    if (std::find(held_fittable.begin(), held_fittable.end(), name) == held_fittable.end()) {
      throw io::InputError(JoinedPaths(paths), 0, 0,
                           "--effect " + name + " is fitted from free motion, and no log holds a "
                           "second of it (a joint faster than 0.05 rad/s, nothing holding the tip)",
                           "add a log of the arm moving freely");
    }
  }
  if (!on_held.empty()) {
    fits.held = estimation::FitEffectsOnLogs(named, result->parameters, on_held, {});
    result->parameters = estimation::WithFittedEffects(result->parameters, fits.held->fitted,
                                                       "pliant identify on " + JoinedPaths(fits.held->logs));
  }
  return fits;
}

std::string EffectFitsText(const EffectFits& fits) {
  return (fits.free_motion ? FreeText(*fits.free_motion) : "") + (fits.held ? HeldText(*fits.held) : "");
}

void AddEffectFitsJson(const EffectFits& fits, nlohmann::json* json) {
  if (fits.free_motion) (*json)["free_motion_fit"] = estimation::FreeMotionFitJson(*fits.free_motion);
  if (const auto& h = fits.held) {
    (*json)["effects_fit"] = {{"logs", h->logs}, {"samples", h->samples},
                              {"segments", h->segments},
                              {"effects", estimation::EffectFindingsJson(h->fitted.effects)},
                              {"heldout_rms_given_mm", h->rms_given_mm},
                              {"heldout_rms_refit_mm", h->rms_refit_mm},
                              {"heldout_rms_with_effects_mm", h->rms_with_effects_mm},
                              {"notes", h->notes}};
  }
}

}  // namespace pliant::cli
