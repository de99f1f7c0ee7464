// Closed-form checks of the shaft's damping, the one formula the simulator
// (hold 0 or 1) and the filter (hold g, a constant) share.
#include "pliant/models/effects/shaft_damping.h"

#include <gtest/gtest.h>

#include <ceres/jet.h>

namespace pliant::models {
namespace {

TEST(ShaftDamping, IsDampingTimesHoldTimesBendRate) {
  // On the wall: 0.02 N·m·s/rad at 0.5 rad/s is 0.01 N·m, of the rate's sign.
  EXPECT_DOUBLE_EQ(ShaftDampingTorque(0.02, 0.5, 1.0), 0.01);
  EXPECT_DOUBLE_EQ(ShaftDampingTorque(0.02, -0.5, 1.0), -0.01);
  // Inside the clearance the shaft touches nothing: no torque at any rate.
  EXPECT_DOUBLE_EQ(ShaftDampingTorque(0.02, 3.0, 0.0), 0.0);
  // Half held, half the torque; no damping, none.
  EXPECT_DOUBLE_EQ(ShaftDampingTorque(0.02, 0.5, 0.5), 0.005);
  EXPECT_DOUBLE_EQ(ShaftDampingTorque(0.0, 0.5, 1.0), 0.0);
}

TEST(ShaftDamping, ItsDerivativeInTheRateIsTheHeldDamping) {
  using Jet = ceres::Jet<double, 1>;
  const Jet torque = ShaftDampingTorque(0.02, Jet(0.5, 0), 0.25);
  EXPECT_DOUBLE_EQ(torque.a, 0.0025);
  EXPECT_DOUBLE_EQ(torque.v[0], 0.005);  // c_s·g
}

}  // namespace
}  // namespace pliant::models
