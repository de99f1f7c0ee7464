#pragma once
// A simulation scenario: which of the paper's experiments to run (its
// protocol), the instrument's truth, the arm's dynamics, controller and
// sensors, and the hidden effects to switch on. Read from JSON
// (experiments/scenarios/*.json, docs/simulator.md); unknown keys are errors.
// Every section but the protocol and the truth may be left out: the defaults
// below are the documented Classic PSM values.

#include <array>
#include <cstdint>
#include <map>
#include <string>
#include <vector>

#include <Eigen/Core>

#include "pliant/models/parameters.h"

namespace pliant::experiments {

enum class ExperimentType { kBiasSweep, kClampedBeam, kDivot, kFreeMotion };

/// "bias_sweep", "clamped_beam", "divot", "free_motion".
const char* ExperimentName(ExperimentType type);

/// Paper §3: each joint through its range in steps, tip free, a hold at each.
struct BiasSweepProtocol {
  std::vector<double> depths_m;
  double step_deg = 5.0;
  std::array<double, 2> joint1_range_deg{-90.0, 90.0};
  std::array<double, 2> joint2_range_deg{-50.0, 50.0};
  double move_s = 0.3;    ///< minimum-jerk move between steps
  double settle_s = 0.3;  ///< wait before the hold samples
  int hold_samples = 20;
};

/// Paper §3 and Fig. 3: the tip clamped to a beam; tip steps until
/// |effort| > limit, reverse to the limit the other way, back past the start.
struct ClampedBeamProtocol {
  std::vector<double> depths_m;
  std::vector<int> joints{1, 2};
  double tip_step_m = 0.25e-3;
  double effort_limit_nm = 1.0;
  Eigen::Vector2d clamp_angle_rad{0.0, 0.0};
  double move_s = 0.1;
  double settle_s = 0.2;
  int hold_samples = 20;
  int max_steps_per_leg = 1000;  ///< safety stop if the limit is never reached
};

/// Paper §3, Figs. 7-8: the tip in a divot; pushes along directions in the
/// (joint 1, joint 2) torque plane at each depth, peak torque and speed.
struct DivotProtocol {
  std::vector<double> depths_m;
  std::vector<double> directions_deg;  ///< 0: +joint 1, 90: +joint 2
  std::vector<double> peak_torques_nm;
  std::vector<double> speeds_rad_s;    ///< of the commanded joint motion
  Eigen::Vector2d divot_angle_rad{0.1, -0.2};
  double hold_s = 1.0;
  double rest_s = 0.5;
};

/// A smooth multi-sine trajectory of all three joints, tip free.
struct FreeMotionProtocol {
  double duration_s = 30.0;
  Eigen::Vector2d amplitude_rad{0.6, 0.35};
  Eigen::Vector2d frequency_hz{0.07, 0.11};
  double depth_mid_m = 0.155;
  double depth_amplitude_m = 0.05;
  double depth_frequency_hz = 0.05;
  double ramp_s = 2.0;  ///< smooth fade-in of the amplitudes
};

/// The instrument's true parameters. joints[j] holds the compliance law, its
/// valid depth range, the bias table tau0(q) and the backlash delta.
struct Truth {
  std::array<models::JointParameters, 2> joints;
  Eigen::Vector2d backlash_centre_rad{0.0, 0.0};  ///< the clearance off-centre
  /// Where the shaft starts inside its clearance, rad from its centre (|·| < δ):
  /// wherever the last motion left it. 0: in the middle.
  Eigen::Vector2d initial_shaft_offset_rad{0.0, 0.0};
  Eigen::Vector2d bias_depth_slope_nm_per_m{0.0, -0.2419};
  double bias_reference_depth_m = 0.155;
};

/// Motor side of joints 1 and 2 (reflected at the joint).
struct JointDynamics {
  Eigen::Vector2d inertia_kg_m2{0.08, 0.08};
};

/// The instrument beyond the clearance. Light, so a free tip follows the
/// cannula wall closely; the shaft's own damping acts only in contact.
struct TipDynamics {
  double inertia_kg_m2 = 2e-6;
  double damping_nm_s_per_rad = 2e-4;
  double shaft_damping_nm_s_per_rad = 0.02;
};

/// Discrete PID at the dVRK period, effort saturated at the ftmax limit.
struct ControllerSettings {
  double rate_hz = 1500.0;
  Eigen::Vector2d kp_nm_per_rad{150.0, 150.0};
  Eigen::Vector2d ki_nm_per_rad_s{1.0, 1.0};
  Eigen::Vector2d kd_nm_s_per_rad{5.0, 5.0};
  double effort_limit_nm = 3.316;
  double integral_limit_nm = 1.0;
  double velocity_filter_hz = 100.0;
};

struct SensorSettings {
  double encoder_count_rad = 7.7e-6;
  double depth_count_m = 1.3e-6;
  double effort_noise_sd_nm = 0.01;
  double effort_count_nm = 4.7e-4;
  double effort_delay_s = 0.0;  ///< effort samples lag the encoder samples
  bool tracker = false;         ///< write q1_ref, q2_ref
  double tracker_noise_sd_rad = 5e-5;
};

/// An effect of the catalogue switched on in the truth, with the parameters
/// the scenario sizes (the others keep their catalogue defaults).
struct HiddenEffect {
  std::string name;
  std::map<std::string, double> parameters;
};

enum class LogMode {
  kAll,        ///< every controller sample (thinned by every_n_periods)
  kHolds,      ///< only the hold samples
  kHoldMeans,  ///< one row per hold: the mean of its samples (the paper's averages)
};

struct LogSettings {
  LogMode mode = LogMode::kAll;
  int every_n_periods = 1;
};

/// CVODE BDF tolerances (docs/simulator.md).
struct IntegratorSettings {
  double relative_tolerance = 1e-4;
  double angle_tolerance_rad = 1e-7;
  double velocity_tolerance_rad_s = 1e-4;
};

struct Scenario {
  std::string name;  ///< the file's stem
  std::string description;
  ExperimentType type = ExperimentType::kFreeMotion;
  BiasSweepProtocol bias_sweep;
  ClampedBeamProtocol clamped_beam;
  DivotProtocol divot;
  FreeMotionProtocol free_motion;
  Truth truth;
  JointDynamics joint;
  TipDynamics tip;
  ControllerSettings controller;
  SensorSettings sensors;
  std::vector<HiddenEffect> hidden_effects;
  LogSettings log;
  IntegratorSettings integrator;
};

/// The paper's truth: K1(L), K2(L) of eqs. (3)-(4) on 0.09-0.22 m, the dVRK
/// file's backlash (0.008478, 0.007176 rad) and bias, tau_min of §2.
Truth DefaultTruth();

/// Reads a scenario file. `overrides` are "key=value" with a dotted key
/// ("experiment.depths_m") and a JSON value ("[0.1,0.2]"; bare words are
/// strings), applied before validation. Throws io::InputError naming the file
/// and line (or the override) of every problem.
Scenario ReadScenario(const std::string& path, const std::vector<std::string>& overrides = {});

/// The same from text; `file` names it in messages and gives the name.
Scenario ParseScenario(const std::string& text, const std::string& file,
                       const std::vector<std::string>& overrides = {});

}  // namespace pliant::experiments
