// Closed-form checks of smooth.
#include "pliant/models/smooth.h"

#include <gtest/gtest.h>


namespace pliant::models {
namespace {

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

}  // namespace
}  // namespace pliant::models
