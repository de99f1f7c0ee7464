// Closed-form checks of bias_torque.
#include "pliant/models/effects/bias_torque.h"

#include <gtest/gtest.h>


namespace pliant::models {
namespace {

TEST(BiasTorqueEffect, InterpolatesLinearlyAndHoldsBeyondTheEnds) {
  const BiasTorqueEffect bias({{-0.1, 0.0, 0.1}, {0.3, 0.1, 0.2}}, {{0.0}, {-0.05}});
  const std::vector<double> values = {0.3, 0.1, 0.2, -0.05};
  JointState<double> s;
  s.encoder_angle_rad << 0.05, 0.7;
  EXPECT_NEAR(bias(values.data(), s)[0], 0.15, 1e-15);
  EXPECT_DOUBLE_EQ(bias(values.data(), s)[1], -0.05);
  s.encoder_angle_rad << -0.075, 0.0;
  EXPECT_NEAR(bias(values.data(), s)[0], 0.25, 1e-15);
  s.encoder_angle_rad << -2.0, 0.0;
  EXPECT_DOUBLE_EQ(bias(values.data(), s)[0], 0.3);
  s.encoder_angle_rad << 2.0, 0.0;
  EXPECT_DOUBLE_EQ(bias(values.data(), s)[0], 0.2);
  EXPECT_EQ(bias.Parameters().size(), 4u);
  EXPECT_EQ(bias.Parameters()[3].name, "tau0_2[0]");
}

}  // namespace
}  // namespace pliant::models
