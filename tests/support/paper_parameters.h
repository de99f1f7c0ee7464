#pragma once
// The paper's parameters built in code, so model tests need no file reader.
#include "pliant/models/parameters.h"

namespace pliant::models::testing {

inline ModelParameters PaperParameters() {
  ModelParameters p;
  p.joints[0].compliance.cubic.coefficients = {639.16, -432.35, 136.32, 3.12};
  p.joints[1].compliance.cubic.coefficients = {3163.17, -1969.15, 448.92, -6.00};
  p.joints[0].backlash_rad = 0.008478;
  p.joints[1].backlash_rad = 0.007176;
  p.joints[0].tau_min_nm = p.joints[0].deadzone_width_nm = 0.1;
  p.joints[1].tau_min_nm = p.joints[1].deadzone_width_nm = 0.2;
  p.joints[0].bias_torque = {{-1.588, 1.588}, {0.199, 0.199}};
  p.joints[1].bias_torque = {{-0.925, 0.925}, {-0.0029145, -0.0029145}};
  for (auto& joint : p.joints) {
    joint.depth_min_m = 0.09;
    joint.depth_max_m = 0.22;
  }
  return p;
}

}  // namespace pliant::models::testing
