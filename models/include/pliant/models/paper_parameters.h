#pragma once
// The paper's model, the one place its numbers are written in code. data/paper.json
// carries the same values with their sources (a test checks they agree).

#include "pliant/models/parameters.h"

namespace pliant::models {

/// K1(L), K2(L) of the paper's equations (3) and (4) on the 0.09–0.22 m it was
/// fitted on (§3); tau_min 0.1 / 0.2 N·m (§2), also the dead-zone width;
/// backlash 0.008478 / 0.007176 rad and a flat bias of 0.199 / −0.0029145 N·m
/// from the dVRK 2017 compensation parameter file (the paper publishes neither).
ModelParameters PaperParameters();

}  // namespace pliant::models
