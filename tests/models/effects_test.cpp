// The built-in effects against closed-form values.
#include <gtest/gtest.h>

#include "paper_parameters.h"
#include "pliant/models/effects/backlash.h"
#include "pliant/models/effects/bias_torque.h"
#include "pliant/models/effects/compliance.h"
#include "pliant/models/smooth.h"

namespace pliant::models {
namespace {

JointState<double> Loaded(double tau1, double tau2, double depth = 0.15) {
  JointState<double> s;
  s.insertion_depth_m = depth;
  s.external_torque_nm << tau1, tau2;
  return s;
}

TEST(SmoothSaturation, ReachesOneExactlyAndSmoothly) {
  EXPECT_DOUBLE_EQ(SmoothSaturation(1.0), 1.0);
  EXPECT_DOUBLE_EQ(SmoothSaturation(-1.0), -1.0);
  EXPECT_DOUBLE_EQ(SmoothSaturation(3.0), 1.0);
  EXPECT_DOUBLE_EQ(SmoothSaturation(0.0), 0.0);
  EXPECT_NEAR(SmoothSaturation(0.5), (7.5 - 1.25 + 0.09375) / 8.0, 1e-15);
  // Slope at the end of the ramp vanishes: S(1 − h) = 1 − O(h³).
  const double h = 1e-3;
  EXPECT_LT(1.0 - SmoothSaturation(1.0 - h), 3.0 * h * h * h);
  EXPECT_NEAR(SmoothSaturation(-0.3), -SmoothSaturation(0.3), 1e-16);
}

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

TEST(ComplianceEffect, IsKTimesTheExternalTorque) {
  const ComplianceEffect compliance;  // the paper's equations (3) and (4)
  const std::vector<double> c = {639.16, -432.35, 136.32, 3.12, 3163.17, -1969.15, 448.92, -6.0};
  const auto bend = compliance(c.data(), Loaded(0.5, -1.0));
  EXPECT_NEAR(bend[0], 0.5 / 15.99729, 1e-12);
  EXPECT_NEAR(bend[1], -1.0 / 27.70782375, 1e-12);
  // Below the calibrated range the depth is clamped, never evaluated where 1/K2 < 0.
  const auto shallow = compliance(c.data(), Loaded(0.5, -1.0, 0.01));
  EXPECT_NEAR(shallow[1], -1.0 / 20.75863593, 1e-12);
}

TEST(BacklashSignEffect, IsDeltaTimesTheSignOfTheLoad) {
  const BacklashSignEffect backlash;
  const std::vector<double> delta = {0.008478, 0.007176};
  EXPECT_EQ(backlash(delta.data(), Loaded(0.3, -1e-9)), Vec2<double>(0.008478, -0.007176));
  EXPECT_EQ(backlash(delta.data(), Loaded(0.0, 2.0)), Vec2<double>(0.0, 0.007176));
}

TEST(BacklashDeadZoneEffect, CrossesTheClearanceWithinTheWidth) {
  const BacklashDeadZoneEffect backlash;
  const std::vector<double> p = {0.008, 0.007, 0.1, 0.2};
  EXPECT_EQ(backlash(p.data(), Loaded(0.1, -0.2)), Vec2<double>(0.008, -0.007));
  EXPECT_EQ(backlash(p.data(), Loaded(5.0, -5.0)), Vec2<double>(0.008, -0.007));
  const auto half = backlash(p.data(), Loaded(0.05, 0.1));
  EXPECT_NEAR(half[0], 0.008 * SmoothSaturation(0.5), 1e-16);
  EXPECT_NEAR(half[1], 0.007 * SmoothSaturation(0.5), 1e-16);
}

}  // namespace
}  // namespace pliant::models
