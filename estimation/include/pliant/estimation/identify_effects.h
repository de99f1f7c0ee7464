#pragma once
// identify's --effect (pliant.identify's effects=): each named catalogue
// effect fitted where it acts — the arm's own dynamics (FittedFromFreeMotion)
// on the logs' free motion, the others on their held-tip rows — into the
// identified parameters. Shared by the command and the Python module.

#include <optional>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "pliant/estimation/effect_fit.h"
#include "pliant/estimation/free_motion_fit.h"
#include "pliant/estimation/identification.h"
#include "pliant/io/log.h"

namespace pliant::estimation {

struct EffectFits {
  std::optional<FreeMotionFit> free_motion;
  std::optional<LogEffectFit> held;
  bool any() const { return free_motion || held; }
};

/// io::InputError for a name the catalogue lacks, one of the base model's,
/// or one given twice: checked before any log is read, so a typo costs nothing.
void CheckIdentifyEffectNames(const std::vector<std::string>& names);

/// Fits `names` on `logs` (read from `paths`) into result->parameters: the
/// effects that read only the joints' motion on the free motion when a log
/// holds a second of it, the rest (and those, without free motion) on the
/// held tip. Throws io::InputError when an effect has nowhere to be fitted.
EffectFits FitEffects(const std::vector<std::string>& names, const std::vector<io::Log>& logs,
                      const std::vector<std::string>& paths, IdentificationResult* result);

/// The parameters with only the effects in `names` (what a second pass takes
/// out of the efforts: the base's own, a held friction, stays in).
models::ModelParameters WithOnlyTheNamed(models::ModelParameters parameters,
                                         const std::vector<std::string>& names);

/// Whether the parameters hold an effect on the measured effort (internal torque).
bool ReadsTheEffort(const models::ModelParameters& parameters);

/// "free_motion_fit" and "effects_fit" (the held tip's), for identify --json.
void AddEffectFitsJson(const EffectFits& fits, nlohmann::json* json);

}  // namespace pliant::estimation
