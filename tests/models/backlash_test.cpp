// Closed-form checks of backlash.
#include "pliant/models/effects/backlash.h"

#include <gtest/gtest.h>

#include "loaded_state.h"

#include "pliant/models/smooth.h"

namespace pliant::models {
namespace {

using testing::Loaded;

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
