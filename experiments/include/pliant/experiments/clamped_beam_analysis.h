#pragma once
// The paper's analysis of the clamped-beam experiment (§4, Fig. 5): at each
// depth and for each joint, a straight line of effort against encoder angle
// for each cannula wall the shaft bears on. The slope is 1/K(L); the
// horizontal distance between the two lines is the clearance, 2·delta.
//
// The holds are split by the sign of the load (effort minus the unloaded
// effort of the first hold): with a real clearance the data of one direction
// of motion lie on both walls (unloading one, then loading the other), so the
// wall, not the direction, names the branch. Holds with |load| below
// min_load_nm (inside or at the edge of the clearance) are left out.

#include <vector>

#include "pliant/experiments/simulator.h"

namespace pliant::experiments {

struct LineFit {
  double slope = 0.0;      ///< N·m/rad
  double intercept = 0.0;  ///< N·m at 0 rad
  int points = 0;
  /// Angle (rad) at which the line reaches an effort (N·m).
  double AngleAt(double effort_nm) const { return (effort_nm - intercept) / slope; }
};

/// Least-squares y = slope·x + intercept.
LineFit FitLine(const std::vector<double>& x, const std::vector<double>& y);

struct ClampedBeamFit {
  int joint = 0;
  double depth_m = 0.0;
  double unloaded_effort_nm = 0.0;  ///< the first hold, tip just clamped
  LineFit upper_wall;               ///< positive load
  LineFit lower_wall;               ///< negative load
  double gap_rad = 0.0;             ///< distance between the lines at the unloaded effort
  // The run's holds, for plotting: encoder angle, effort, direction of motion.
  std::vector<double> angle_rad, effort_nm;
  std::vector<int> direction;
};

/// One fit per (depth, joint) run of a clamped-beam simulation, in run order.
std::vector<ClampedBeamFit> FitClampedBeam(const SimulationResult& result,
                                           double min_load_nm = 0.1);

}  // namespace pliant::experiments
