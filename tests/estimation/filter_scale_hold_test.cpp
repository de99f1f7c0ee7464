// The compliance scale learns only from loads that hold the shaft on its wall
// (FilterOptions::scale_hold_exponent). A real shaft meets its wall as soon as
// a load pushes it; the model's shaft reaches it only at the dead-zone width
// w. Below w the encoder sits beyond what the model's pull allows, and a
// filter that lets s learn there reads the gap as compliance.
#include <cmath>
#include <string>

#include <gtest/gtest.h>

#include "../support/steady_hold.h"
#include "pliant/estimation/filter.h"

namespace pliant::estimation {
namespace {

using testing::ScaleTrace;
using testing::TraceScaleOverHold;

FilterOptions WithExponent(double hold_exponent) {
  FilterOptions o;
  o.scale_hold_exponent = hold_exponent;
  return o;
}

// s after a 3 s hold with the filter's own effort noise.
double ScaleAfterHold(double hold_exponent, double load_fraction) {
  return TraceScaleOverHold(WithExponent(hold_exponent), load_fraction, 3.0, 1.0).at_end;
}

// Measured (seed 5), s after the hold, exponent 0 / 4: at 0.5 w 0.982 /
// 0.997; at 3 w 1.0035 / 1.0033 (sd(s) ≈ 0.01 after 3 s).
TEST(FilterScaleHold, HalfTheWidthDoesNotTeachTheScale) {
  EXPECT_GT(std::abs(ScaleAfterHold(0.0, 0.5) - 1.0), 0.01);
  EXPECT_LT(std::abs(ScaleAfterHold(FilterOptions().scale_hold_exponent, 0.5) - 1.0), 0.005);
}

TEST(FilterScaleHold, ThreeWidthsStillTeachIt) {
  EXPECT_NEAR(ScaleAfterHold(FilterOptions().scale_hold_exponent, 3.0), 1.0, 0.005);
}

// A known defect, kept as the next fix's target (run with
// --gtest_also_run_disabled_tests): held at w, s falls to 0.91 in 3 s
// (exponent 0 / 4 — 0.8 w: 0.938 / 0.927, w: 0.904 / 0.909, 1.2 w: 0.978 /
// 0.968, 1.5 w: 1.013 / 1.009). Until the held load's rate was bounded
// (FilterOptions::bound_held_load_rate) it fell to 0.71: the EKF's
// errors-in-variables bias on the bilinear term s·K·tau, whose ∂h/∂s is K·tau
// at the estimated load, so that a load free to follow the effort noise made
// that noise a regressor of s (the tests below;
// docs/decisions/0004-filter-held-load-rate.md). What is left at w is the
// partial hold: there the bound applies only in part (g < 1).
TEST(FilterScaleHold, DISABLED_AtTheWidthTheScaleHolds) {
  EXPECT_NEAR(ScaleAfterHold(FilterOptions().scale_hold_exponent, 1.0), 1.0, 0.05);
}

// The cause, pinned, with the load's rate left free as before the bound:
// without effort noise the same hold leaves s where the ramp put it (measured
// 0.93453 → 0.93442 from 1 s to 3.5 s); with the filter's own noise it falls
// 0.892 → 0.713 over the same 2.5 s.
TEST(FilterScaleHold, WithoutEffortNoiseASteadyHoldDoesNotMoveTheScale) {
  FilterOptions o;
  o.bound_held_load_rate = false;
  const ScaleTrace quiet = TraceScaleOverHold(o, 1.0, 3.0, 0.0);
  EXPECT_NEAR(quiet.at_end, quiet.after_1s, 0.002);
  const ScaleTrace noisy = TraceScaleOverHold(o, 1.0, 3.0, 1.0);
  EXPECT_LT(noisy.at_end, noisy.after_1s - 0.1);
}

// Over 19 s held at 3 w, s stays within 0.015 of the truth (measured 1.0027;
// 0.9929 with the load's rate free, which at 1.5 w gave 0.658 where the
// bound keeps 0.978: tests/estimation/filter_held_load_test.cpp).
TEST(FilterScaleHold, ALongHoldAtThreeWidthsKeepsTheScale) {
  EXPECT_NEAR(TraceScaleOverHold(FilterOptions(), 3.0, 19.0, 1.0).at_end, 1.0, 0.015);
}

TEST(FilterScaleHold, ExponentMustBeFiniteAndNonNegative) {
  FilterOptions o;
  std::string error;
  o.scale_hold_exponent = -1.0;
  EXPECT_FALSE(o.IsValid(&error));
  EXPECT_NE(error.find("scale_hold_exponent"), std::string::npos);
  o.scale_hold_exponent = std::nan("");
  EXPECT_FALSE(o.IsValid(&error));
  o.scale_hold_exponent = 0.0;
  EXPECT_TRUE(o.IsValid(&error));
}

}  // namespace
}  // namespace pliant::estimation
