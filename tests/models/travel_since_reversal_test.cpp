#include "pliant/models/travel_since_reversal.h"

#include <cmath>

#include <gtest/gtest.h>

#include "pliant/models/effects/held_friction.h"

namespace pliant::models {
namespace {

TEST(TravelSinceReversal, CountsTravelFromTheLastTurningPoint) {
  TravelSinceReversal travel(2e-4);
  const double nan = std::nan("");
  EXPECT_EQ(travel.Update({0.0, nan})[0], 0.0);     // never moved
  EXPECT_EQ(travel.Update({1e-4, nan})[0], 0.0);    // inside the threshold
  EXPECT_NEAR(travel.Update({1e-3, nan})[0], 1e-3, 1e-15);
  EXPECT_NEAR(travel.Update({3e-3, nan})[0], 3e-3, 1e-15);
  EXPECT_NEAR(travel.Update({2.9e-3, nan})[0], 2.9e-3, 1e-15);  // jitter: no reversal
  EXPECT_NEAR(travel.Update({2e-3, nan})[0], -1e-3, 1e-15);     // reversed at 3e-3
  EXPECT_NEAR(travel.Update({-1e-3, nan})[0], -4e-3, 1e-15);
  EXPECT_EQ(travel.Update({0.0, nan})[1], 0.0);  // an unrecorded joint stays at 0
}

TEST(HeldFriction, IsMinusFJustAfterAReversalAndTendsToPlusF) {
  const HeldFrictionEffect effect;
  const double p[3] = {0.1, 0.2, 0.002};
  JointState<double> s;
  s.travel_since_reversal_rad << 1e-12, -0.002;
  const auto tau = effect(p, s);
  EXPECT_NEAR(tau[0], -0.1, 1e-9);  // the previous (negative) motion's friction
  EXPECT_NEAR(tau[1], -0.2 * (1.0 - 2.0 * std::exp(-1.0)), 1e-12);
  s.travel_since_reversal_rad << 0.05, 0.0;
  EXPECT_NEAR(effect(p, s)[0], 0.1, 1e-10);
  EXPECT_EQ(effect(p, s)[1], 0.0);
}

}  // namespace
}  // namespace pliant::models
