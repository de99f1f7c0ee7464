// pliant identify --effect: the text the command prints of the effects it
// fitted (the fits themselves: estimation/identify_effects.h).
#pragma once

#include <string>

#include "pliant/estimation/identify_effects.h"
#include "pliant/estimation/identify_logs.h"

namespace pliant::cli {

using estimation::EffectFits;
using estimation::JoinedPaths;  // the logs, as an error message names them all

std::string EffectFitsText(const EffectFits& fits);

}  // namespace pliant::cli
