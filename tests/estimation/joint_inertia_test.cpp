// The arm's inertia as a catalogue effect (models/effects/joint_inertia.h):
// J·a per joint, in closed form, with derivatives the Jacobian check agrees on.
#include <gtest/gtest.h>

#include "pliant/estimation/effect_catalogue.h"
#include "pliant/estimation/jacobian_check.h"

namespace pliant {
namespace {

TEST(JointInertia, IsTheEffortThatAcceleratesTheArm) {
  const auto effect = estimation::EffectCatalogue::Global().Create("joint_inertia");
  EXPECT_EQ(effect->Info().channel, models::Channel::kInternalTorque);
  const std::vector<double> inertia = {0.15, 0.08};
  models::JointState<double> s;
  s.acceleration_rad_s2 << 2.0, -0.5;
  s.velocity_rad_s << 0.4, -0.3;  // speed alone puts nothing in
  const auto torque = effect->Evaluate(inertia.data(), s);
  EXPECT_DOUBLE_EQ(torque[0], 0.30);
  EXPECT_DOUBLE_EQ(torque[1], -0.04);
  s.acceleration_rad_s2.setZero();
  EXPECT_EQ(effect->Evaluate(inertia.data(), s).norm(), 0.0);
  s.acceleration_rad_s2 << 2.0, -0.5;
  const auto check = estimation::CheckEffectJacobians(*effect, inertia, s);
  EXPECT_TRUE(check.ok) << check.Report();
  // ∂τ1/∂a1 = J1 (a1, a2 come before the state's last two inputs, K1 and K2).
  EXPECT_DOUBLE_EQ(check.autodiff(0, 2 + models::kJointStateSize - 4), 0.15);
}

}  // namespace
}  // namespace pliant
