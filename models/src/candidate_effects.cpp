// Parameter specs of the effects added as diagnosis candidates (issue 6).
#include "pliant/models/effects/backlash_depth.h"
#include "pliant/models/effects/bias_torque_cross_joint.h"
#include "pliant/models/effects/effort_delay.h"

namespace pliant::models {

std::vector<ParameterSpec> BacklashDepthEffect::Parameters() const {
  // The dVRK file's delta is 0.007-0.008 rad; a worn seal or a depth-varying
  // lever changes it by a fraction of that over the 0.09-0.22 m range. Widths
  // as the base model's dead zone (paper's tau_min).
  return {{"clearance1", "rad", 0.0, -0.01, 0.01, 0.003},
          {"clearance2", "rad", 0.0, -0.01, 0.01, 0.003},
          {"growth1", "rad/m", 0.0, -0.2, 0.2, 0.05},
          {"growth2", "rad/m", 0.0, -0.2, 0.2, 0.05},
          {"width1", "N·m", 0.1, 1e-3, 1.0, 0.1},
          {"width2", "N·m", 0.2, 1e-3, 1.0, 0.1}};
}

std::vector<ParameterSpec> BiasTorqueCrossJointEffect::Parameters() const {
  // A few hundredths of a N·m: the spread of the paper's Fig. 4 bias curves.
  return {{"cross1", "N·m", 0.0, -0.5, 0.5, 0.05}, {"cross2", "N·m", 0.0, -0.5, 0.5, 0.05}};
}

std::vector<ParameterSpec> EffortDelayEffect::Parameters() const {
  // The dVRK's effort is the motor current, filtered and read a bus cycle or
  // two after the encoders: milliseconds to tens of milliseconds.
  return {{"delay", "s", 0.0, -0.05, 0.2, 0.02}};
}

}  // namespace pliant::models
