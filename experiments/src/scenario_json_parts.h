#pragma once
// The sections of a scenario file, read by separate translation units.
#include "pliant/experiments/scenario.h"
#include "scenario_reader.h"

namespace pliant::experiments::detail {

/// The "experiment" section; the truth must be read first (depth ranges).
void ReadExperiment(const ScenarioReader& reader, const json& experiment, Scenario& out);

}  // namespace pliant::experiments::detail
