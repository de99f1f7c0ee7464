#pragma once
// A joint state under external load, for effect tests.
#include "pliant/models/effect.h"

namespace pliant::models::testing {

inline JointState<double> Loaded(double tau1_nm, double tau2_nm, double depth_m = 0.15) {
  JointState<double> s;
  s.insertion_depth_m = depth_m;
  s.external_torque_nm << tau1_nm, tau2_nm;
  return s;
}

}  // namespace pliant::models::testing
