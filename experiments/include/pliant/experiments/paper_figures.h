#pragma once
// The simulator's analogues of the paper's figures, drawn with plot.h.

#include <string>

#include "pliant/experiments/scenario.h"
#include "pliant/experiments/simulator.h"

namespace pliant::experiments {

/// Fig. 4: the mean effort of each hold of a bias sweep against the joint
/// angle, one series per depth, a panel per joint.
void PlotBiasSweep(const SimulationResult& result, const std::string& path);

/// Fig. 5: effort against encoder angle on the clamped beam at the depth
/// nearest `depth_m` (the paper's first depth by default), holds marked by the
/// direction of motion, with the best-fit line of each branch (cannula wall).
void PlotClampedBeam(const SimulationResult& result, const std::string& path,
                     double depth_m = 0.09);

/// Figs. 7-8 (divot) and free motion: encoder minus true angle over time.
void PlotDeflection(const SimulationResult& result, const std::string& path);

/// The figure that fits the scenario's experiment (one of the above).
void PlotExperiment(const Scenario& scenario, const SimulationResult& result,
                    const std::string& path);

}  // namespace pliant::experiments
