// The default truth: the paper's compliance, the dVRK file's backlash, and a
// bias torque shaped like the paper's Fig. 4.
#include <cmath>

#include "pliant/models/paper_parameters.h"
#include "pliant/experiments/scenario.h"

namespace pliant::experiments {
namespace {

// A smooth counterbalance residual sampled at 9 knots across the range. The
// mean levels are the dVRK 2017 parameter file's (0.199 N·m for joint 1;
// joint 2's law at mid depth, −0.0029 N·m); the variation with angle (a few
// hundredths to a tenth of a N·m) is of the size the paper's Fig. 4 shows.
models::BiasTorqueTable Table(double limit_rad, double mean_nm, double sine_nm, double cosine2_nm) {
  models::BiasTorqueTable table;
  for (int i = 0; i <= 8; ++i) {
    const double q = -limit_rad + 2.0 * limit_rad * i / 8.0;
    table.angle_rad.push_back(q);
    table.torque_nm.push_back(mean_nm + sine_nm * std::sin(q) + cosine2_nm * std::cos(2.0 * q));
  }
  return table;
}

}  // namespace

const char* ExperimentName(ExperimentType type) {
  switch (type) {
    case ExperimentType::kBiasSweep:
      return "bias_sweep";
    case ExperimentType::kClampedBeam:
      return "clamped_beam";
    case ExperimentType::kDivot:
      return "divot";
    case ExperimentType::kFreeMotion:
      return "free_motion";
  }
  return "?";
}

Truth DefaultTruth() {
  Truth truth;
  // The paper's compliance, tau_min and range and the dVRK file's backlash and
  // bias level, with a bias that varies with the angle as in the paper's Fig. 4.
  truth.joints = models::PaperParameters().joints;
  truth.joints[0].bias_torque = Table(1.588, 0.199, 0.06, -0.025);
  truth.joints[1].bias_torque = Table(0.925, -0.0029145, 0.12, 0.02);
  return truth;
}

}  // namespace pliant::experiments
