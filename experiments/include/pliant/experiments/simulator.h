#pragma once
// The simulator of PSM joints 1-2: a scenario's protocol drives a discrete
// PID controller at the dVRK period; CVODE integrates the joints, the shaft
// with its compliance and real cannula clearance, and the tip (free or held);
// sensors quantise and add noise. Deterministic for a seed.
//
//   const auto scenario = pliant::experiments::ReadScenario("experiments/scenarios/divot.json");
//   const auto result = pliant::experiments::Simulate(scenario, /*seed=*/1);
//   pliant::io::WriteLog("divot.csv", result.log);

#include <cstdint>
#include <string>
#include <vector>

#include <Eigen/Core>

#include "pliant/experiments/scenario.h"
#include "pliant/io/log.h"

namespace pliant::experiments {

/// One labelled part of a protocol (the log's `segment` column). Segment 0
/// is transit between parts: tip free, nothing measured.
struct SegmentInfo {
  int id = 0;
  int joint = 0;          ///< joint under test (1, 2), 0 when both or none
  double depth_m = 0.0;
  int direction = 0;      ///< +1 / −1: direction of the steps or the push
  std::string label;      ///< e.g. "clamped_beam joint 1 depth 0.09 m leg 2 (-)"
};

/// The means of one hold (the samples a protocol averages at a position).
struct HoldRecord {
  int segment = 0;
  double time_s = 0.0;  ///< of the hold's last sample
  double depth_m = 0.0;
  bool tip_fixed = false;
  Eigen::Vector2d encoder_rad = Eigen::Vector2d::Zero();
  Eigen::Vector2d effort_nm = Eigen::Vector2d::Zero();
  Eigen::Vector2d true_angle_rad = Eigen::Vector2d::Zero();
  Eigen::Vector2d command_rad = Eigen::Vector2d::Zero();
};

struct SimulationStats {
  double simulated_s = 0.0;
  long controller_periods = 0;
  long integrator_steps = 0;
  long rhs_evaluations = 0;
  long contact_events = 0;
};

struct SimulationResult {
  io::Log log;  ///< canonical columns, tip_fixed and segment filled in
  std::vector<SegmentInfo> segments;
  std::vector<HoldRecord> holds;
  SimulationStats stats;
};

/// Runs the scenario. Throws std::runtime_error if the integrator fails.
SimulationResult Simulate(const Scenario& scenario, std::uint64_t seed);

}  // namespace pliant::experiments
