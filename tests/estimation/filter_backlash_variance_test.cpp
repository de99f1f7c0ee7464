// How the filter keeps the backlash offset b inside its clearance
// (BoundBacklashVariance): bounded with a free tip, by scaling b's row of F;
// not bounded with the tip held, where b's process noise is what lets the
// encoders move b rather than the held tip (the Monte Carlo divot study's
// outlier trials: tests/montecarlo/trial_test.cpp).
#include <gtest/gtest.h>

#include "pliant/estimation/filter.h"

namespace pliant::estimation {
namespace {

TEST(BoundBacklashVariance, FreeTipStaysUnderTheUniformsVariance) {
  const double prior = 3.0;
  // Room under the bound: F is kept, the process adds at most the room.
  auto b = BoundBacklashVariance(false, 1.0, 0.5, prior);
  EXPECT_DOUBLE_EQ(b.row_scale, 1.0);
  EXPECT_DOUBLE_EQ(b.process_variance, 0.5);
  b = BoundBacklashVariance(false, 1.0, 5.0, prior);
  EXPECT_DOUBLE_EQ(b.row_scale, 1.0);
  EXPECT_DOUBLE_EQ(b.process_variance, 2.0);
  // F·P·Fᵀ beyond the bound (12 = 4 × 3): b's row is halved, so its variance
  // is scaled by 1/4 onto the bound, and the process adds nothing.
  b = BoundBacklashVariance(false, 12.0, 0.5, prior);
  EXPECT_DOUBLE_EQ(b.row_scale, 0.5);
  EXPECT_DOUBLE_EQ(b.process_variance, 0.0);
}

TEST(BoundBacklashVariance, HeldTipIsNotBounded) {
  const auto b = BoundBacklashVariance(true, 12.0, 5.0, 3.0);
  EXPECT_DOUBLE_EQ(b.row_scale, 1.0);
  EXPECT_DOUBLE_EQ(b.process_variance, 5.0);
}

}  // namespace
}  // namespace pliant::estimation
