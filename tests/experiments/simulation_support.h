#pragma once
// Shared by the simulator tests: the scenario files, shortened by overrides.
#include <string>
#include <vector>

#include "pliant/experiments/scenario.h"
#include "pliant/experiments/simulator.h"
#include "pliant/io/log.h"

namespace pliant::experiments::testing {

inline Scenario Load(const std::string& name, const std::vector<std::string>& sets = {}) {
  return ReadScenario(std::string(PLIANT_SOURCE_DIR) + "/experiments/scenarios/" + name + ".json",
                      sets);
}

inline std::vector<double> Column(const io::Log& log, const char* name) { return log.Column(name); }

}  // namespace pliant::experiments::testing

namespace pliant::experiments::testing {

/// The bias sweep at two depths, simulated once per test program.
inline const Scenario& BiasSweepScenario() {
  static const Scenario s = Load("bias_sweep", {"experiment.depths_m=[0.09,0.21]"});
  return s;
}
inline const SimulationResult& BiasSweepRun() {
  static const SimulationResult r = Simulate(BiasSweepScenario(), 7);
  return r;
}

}  // namespace pliant::experiments::testing
