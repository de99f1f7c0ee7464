#pragma once
// A quasi-static log generator: the instrument tip rests in a divot while the
// controller pushes on it with slowly varying force, as in the paper's last
// experiment (Figs. 7 and 8). It composes the models/ effects for the truth
// (bias torque, compliance K(L)) and adds a backlash with real hysteresis: the
// shaft stays where it is inside the cannula clearance until the load exceeds a
// small sticking torque, then rests on the wall the load pushes it toward.
// Not dynamics (that is the CVODE simulator's job): every sample is in
// equilibrium, which is what the paper's model assumes.

#include <cstdint>
#include <vector>

#include "pliant/io/log.h"
#include "pliant/models/parameters.h"

namespace pliant::experiments {

/// One push: the load ramps from zero to peak along a direction in the
/// (joint 1, joint 2) torque plane, holds, and ramps back to zero.
struct Push {
  double insertion_depth_m = 0.15;
  double direction_rad = 0.0;   ///< 0: +joint 1, pi/2: +joint 2
  double peak_torque_nm = 1.0;  ///< the paper pushes to 1.0 N·m
  double ramp_s = 4.0;
  double hold_s = 2.0;
};

struct PushScenario {
  models::ModelParameters truth;          ///< the instrument's true parameters
  Eigen::Vector2d tip_angle_rad{0.1, -0.2};  ///< where the divot holds the tip
  std::vector<Push> pushes;
  double free_s = 3.0;                    ///< free tip (no load) before the first push
  double sample_rate_hz = 100.0;          ///< ROS topics' default rate
  double encoder_count_rad = 7.7e-6;      ///< Classic PSM joints 1–2
  double effort_noise_sd_nm = 0.01;
  double sticking_torque_nm = 0.03;       ///< load that moves the shaft in the clearance
  std::uint64_t seed = 1;
};

/// The default: pushes along ±joint 1, ±joint 2 and two oblique directions at
/// 0.12 m and 0.18 m, with the paper's parameters as the truth.
PushScenario DefaultDivotScenario(const models::ModelParameters& truth);

/// Columns: t q1 q2 q3 tau1 tau2 v1 v2 q1_true q2_true tip_fixed segment and an
/// auxiliary motor_temperature_c; metadata names the generator and seed.
io::Log GenerateDivotPushLog(const PushScenario& scenario);

}  // namespace pliant::experiments
