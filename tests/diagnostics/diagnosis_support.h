#pragma once
// Short simulated divot logs with a hidden effect, and the model that lacks
// it (the simulator's truth, with the hidden effect off), for the diagnosis
// tests and the false-alarm bench.

#include <string>
#include <vector>

#include "pliant/experiments/scenario.h"
#include "pliant/experiments/simulator.h"
#include "pliant/models/parameters.h"

namespace pliant::testing {

/// The divot scenario cut short: two depths (0.11 and 0.19 m, deeper second),
/// six push directions (±joint 1, ±joint 2, two obliques), one peak torque
/// and one speed, logged at 300 Hz. `hidden` is the JSON object of hidden
/// effects ("{}" for none); `extra` are more scenario overrides.
inline experiments::Scenario ShortDivot(const std::string& hidden,
                                        const std::vector<std::string>& extra = {}) {
  std::vector<std::string> overrides = {
      "experiment.depths_m=[0.11,0.19]",
      "experiment.directions_deg=[0,90,180,270,45,225]",
      "experiment.peak_torques_nm=[1.0]",
      "experiment.speeds_rad_s=[0.05]",
      "experiment.hold_s=0.6",
      "experiment.rest_s=0.3",
      // The model under test has no depth slope in its bias: neither has the truth.
      "truth.bias_torque.depth_slope_nm_per_m=[0,0]",
      "log.every_n_periods=5",
      "sensors.tracker=true",
      "hidden_effects=" + hidden};
  overrides.insert(overrides.end(), extra.begin(), extra.end());
  return experiments::ReadScenario(PLIANT_SOURCE_DIR "/experiments/scenarios/divot.json",
                                   overrides);
}

/// The model the diagnosis is given: the truth's bias table, compliance law,
/// backlash and the paper's dead-zone widths — every effect but the hidden ones.
inline models::ModelParameters ModelOf(const experiments::Scenario& scenario) {
  models::ModelParameters p;
  p.description = "the simulator's truth without its hidden effects";
  for (int j = 0; j < 2; ++j) p.joints[j] = scenario.truth.joints[j];
  return p;
}

}  // namespace pliant::testing
