#include "pliant/models/paper_parameters.h"

namespace pliant::models {

ModelParameters PaperParameters() {
  ModelParameters p;
  p.description = "the paper's model (data/paper.json)";
  auto& j1 = p.joints[0];
  auto& j2 = p.joints[1];
  j1.compliance.cubic.coefficients = {639.16, -432.35, 136.32, 3.12};     // eq. (3)
  j2.compliance.cubic.coefficients = {3163.17, -1969.15, 448.92, -6.00};  // eq. (4)
  j1.tau_min_nm = j1.deadzone_width_nm = 0.1;
  j2.tau_min_nm = j2.deadzone_width_nm = 0.2;
  j1.backlash_rad = 0.008478;
  j2.backlash_rad = 0.007176;
  // dVRK file: joint 2's bias is -0.2419·q3 + 0.03458, taken at mid-range 0.155 m.
  j1.bias_torque = {{-1.588, 1.588}, {0.199, 0.199}};
  j2.bias_torque = {{-0.925, 0.925}, {-0.0029145, -0.0029145}};
  for (auto& joint : p.joints) {
    joint.depth_min_m = 0.09;
    joint.depth_max_m = 0.22;
  }
  return p;
}

}  // namespace pliant::models
