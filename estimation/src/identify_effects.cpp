// identify's --effect, shared by the command and pliant.identify (identify_effects.h).
#include "pliant/estimation/identify_effects.h"

#include <algorithm>

#include "pliant/estimation/effect_catalogue.h"
#include "pliant/estimation/extra_effects.h"
#include "pliant/estimation/identification_report.h"
#include "pliant/estimation/identify_logs.h"
#include "pliant/io/input_error.h"
#include "pliant/io/progress.h"

namespace pliant::estimation {
namespace {

std::vector<NamedLog> Named(const std::vector<io::Log>& logs,
                            const std::vector<std::string>& paths) {
  std::vector<NamedLog> named;
  for (std::size_t i = 0; i < logs.size(); ++i) named.push_back({&logs[i], paths[i]});
  return named;
}

}  // namespace

// Checked before any log is read, so a typo costs nothing.
void CheckIdentifyEffectNames(const std::vector<std::string>& names) {
  // The diagnosis's candidates and the arm's dynamics (fitted from free motion).
  auto candidates = CandidateEffectNames();
  for (const auto& name : FreeMotionEffectNames()) {
    if (std::find(candidates.begin(), candidates.end(), name) == candidates.end())
      candidates.push_back(name);
  }
  const std::string known = JoinedPaths(candidates);
  for (std::size_t i = 0; i < names.size(); ++i) {
    const std::string option = "pliant identify: --effect " + names[i];
    if (!EffectCatalogue::Global().Contains(names[i]))
      throw io::InputError(option, 0, 0, "not in the catalogue", "one of: " + known);
    if (std::find(candidates.begin(), candidates.end(), names[i]) == candidates.end())
      throw io::InputError(option, 0, 0, "is part of the model identify always fits",
                           "name an effect beyond it, one of: " + known);
    if (std::find(names.begin(), names.begin() + long(i), names[i]) != names.begin() + long(i))
      throw io::InputError(option, 0, 0, "is given twice", "give each effect once: it is fitted once");
  }
}

models::ModelParameters WithOnlyTheNamed(models::ModelParameters parameters,
                                         const std::vector<std::string>& names) {
  auto& e = parameters.effects;
  e.erase(std::remove_if(e.begin(), e.end(),
                         [&](const models::EffectParameters& effect) {
                           return std::find(names.begin(), names.end(), effect.name) == names.end();
                         }),
          e.end());
  return parameters;
}

bool ReadsTheEffort(const models::ModelParameters& parameters) {
  const ExtraEffects effects(parameters.effects);
  return std::any_of(effects.models().begin(), effects.models().end(), [](const auto& m) {
    return m->Info().channel == models::Channel::kInternalTorque;
  });
}

EffectFits FitEffects(const std::vector<std::string>& names, const std::vector<io::Log>& logs,
                      const std::vector<std::string>& paths, IdentificationResult* result) {
  EffectFits fits;
  if (names.empty()) return fits;
  io::Progress progress("pliant identify: fitting " + JoinedPaths(names));
  const bool free_motion = std::any_of(logs.begin(), logs.end(), [](const io::Log& log) {
    return FreeMotionSeconds(log) >= 1.0;
  });
  std::vector<std::string> on_free, on_held;
  for (const auto& name : names)
    (free_motion && FittedFromFreeMotion(name) ? on_free : on_held).push_back(name);
  const auto named = Named(logs, paths);
  // The dynamics first: the held-tip fit then keeps them in its model.
  if (!on_free.empty()) {
    fits.free_motion = FitEffectsOnFreeMotion(named, result->parameters, on_free);
    result->parameters = WithFittedEffects(
        result->parameters, fits.free_motion->fitted,
        "pliant identify on the free motion of " + JoinedPaths(fits.free_motion->logs));
  }
  // An effect the diagnosis does not fit on a held tip has nowhere else to go.
  const auto held_fittable = CandidateEffectNames();
  for (const auto& name : on_held) {
    if (std::find(held_fittable.begin(), held_fittable.end(), name) == held_fittable.end()) {
      throw io::InputError(JoinedPaths(paths), 0, 0,
                           "--effect " + name + " is fitted from free motion, and no log holds a "
                           "second of it (a joint faster than 0.05 rad/s, nothing holding the tip)",
                           "add a log of the arm moving freely");
    }
  }
  if (!on_held.empty()) {
    fits.held = FitEffectsOnLogs(named, result->parameters, on_held, {});
    result->parameters = WithFittedEffects(result->parameters, fits.held->fitted,
                                           "pliant identify on " + JoinedPaths(fits.held->logs));
  }
  return fits;
}

void AddEffectFitsJson(const EffectFits& fits, nlohmann::json* json) {
  if (fits.free_motion) (*json)["free_motion_fit"] = FreeMotionFitJson(*fits.free_motion);
  if (const auto& h = fits.held) {
    (*json)["effects_fit"] = {{"logs", h->logs}, {"samples", h->samples},
                              {"segments", h->segments},
                              {"effects", EffectFindingsJson(h->fitted.effects)},
                              {"heldout_rms_given_mm", h->rms_given_mm},
                              {"heldout_rms_refit_mm", h->rms_refit_mm},
                              {"heldout_rms_with_effects_mm", h->rms_with_effects_mm},
                              {"notes", h->notes}};
  }
}

}  // namespace pliant::estimation
