// Closed-form checks of the backlash memory step (backlash_hysteresis.h).
#include "pliant/models/effects/backlash_hysteresis.h"

#include <cmath>

#include <ceres/jet.h>
#include <gtest/gtest.h>

#include "pliant/models/smooth.h"

namespace pliant::models {
namespace {

constexpr double kDelta = 0.008, kWidth = 0.1;

TEST(BacklashHysteresisStep, PullsTheShaftTowardTheWallTheLoadPointsAt) {
  // From the middle, half the width: b+ = g·δ·S(1/2), g = S(1/2)².
  const double s = SmoothSaturation(0.5);
  EXPECT_DOUBLE_EQ(BacklashHysteresisStep(0.0, 0.05, kDelta, kWidth), s * s * kDelta * s);
  // Beyond the width the shaft is on the wall, wherever it was.
  EXPECT_DOUBLE_EQ(BacklashHysteresisStep(-kDelta, 0.3, kDelta, kWidth), kDelta);
  EXPECT_DOUBLE_EQ(BacklashHysteresisStep(0.3 * kDelta, -0.3, kDelta, kWidth), -kDelta);
}

TEST(BacklashHysteresisStep, ALoadNeverPullsTheShaftBackOffItsWall) {
  // On the + wall, the load eased to w/2: the dead-zone position δ·S(1/2) is
  // nearer the middle, but a load only pushes, so the shaft stays.
  EXPECT_DOUBLE_EQ(BacklashHysteresisStep(kDelta, 0.05, kDelta, kWidth), kDelta);
  EXPECT_DOUBLE_EQ(BacklashHysteresisStep(-kDelta, -0.02, kDelta, kWidth), -kDelta);
  // The same shaft under a load the other way is pulled across.
  EXPECT_LT(BacklashHysteresisStep(kDelta, -0.05, kDelta, kWidth), kDelta);
  // A free tip's arm moving on (relax r = 0.2) still lets an unloaded shaft
  // forget its wall: b+ = b − (1 − g)·r·b.
  const double s = SmoothSaturation(0.005 / kWidth), g = s * s;
  EXPECT_DOUBLE_EQ(BacklashHysteresisStep(kDelta, 0.005, kDelta, kWidth, 0.2),
                   kDelta - (1.0 - g) * 0.2 * kDelta);
}

TEST(BacklashHysteresisStep, AConstantHoldLeavesOnlyTheTargetsSlope) {
  // With g passed as a number the Jacobian has no ∂g/∂tau: ∂b+/∂tau = g·δ·S'(tau/w)/w
  // and ∂b+/∂b = 1 − g while the load pushes.
  using Jet = ceres::Jet<double, 2>;
  const double tau = 0.04, b = -0.002;
  const double g = BacklashHold(tau, kWidth);
  const Jet next = BacklashHysteresisStep(Jet(b, 0), Jet(tau, 1), kDelta, kWidth, 0.0, g);
  const double h = 1e-7;
  const double slope =
      (SmoothSaturation((tau + h) / kWidth) - SmoothSaturation((tau - h) / kWidth)) / (2.0 * h);
  EXPECT_NEAR(next.v[1], g * kDelta * slope, 1e-6 * std::abs(g * kDelta * slope));
  EXPECT_DOUBLE_EQ(next.v[0], 1.0 - g);
  EXPECT_DOUBLE_EQ(next.a, BacklashHysteresisStep(b, tau, kDelta, kWidth));
}

}  // namespace
}  // namespace pliant::models
