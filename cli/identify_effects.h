// pliant identify --effect: each named effect fitted where it acts — the arm's
// own dynamics (estimation::FittedFromFreeMotion) on the logs' free motion,
// the others on their held-tip rows — into the identified parameters.
#pragma once

#include <optional>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "pliant/estimation/effect_fit.h"
#include "pliant/estimation/free_motion_fit.h"
#include "pliant/estimation/identification.h"
#include "pliant/estimation/identify_logs.h"
#include "pliant/io/log.h"

namespace pliant::cli {

struct EffectFits {
  std::optional<estimation::FreeMotionFit> free_motion;
  std::optional<estimation::LogEffectFit> held;
  bool any() const { return free_motion || held; }
};

/// Fits `names` on `logs` (read from `paths`) into result->parameters: the
/// effects that read only the joints' motion on the free motion when a log
/// holds a second of it, the rest (and those, without free motion) on the
/// held tip. Throws io::InputError when an effect has nowhere to be fitted.
EffectFits FitEffects(const std::vector<std::string>& names, const std::vector<io::Log>& logs,
                      const std::vector<std::string>& paths,
                      estimation::IdentificationResult* result);

std::string EffectFitsText(const EffectFits& fits);
/// "free_motion_fit" and "effects_fit" (the held tip's), for identify --json.
void AddEffectFitsJson(const EffectFits& fits, nlohmann::json* json);

using estimation::JoinedPaths;  // the logs, as an error message names them all

}  // namespace pliant::cli
