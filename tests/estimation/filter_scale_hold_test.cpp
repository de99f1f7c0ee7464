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

// s after a 3 s hold with the filter's own effort noise.
double ScaleAfterHold(double hold_exponent, double load_fraction) {
  return TraceScaleOverHold(hold_exponent, load_fraction, 3.0, 1.0).at_end;
}

// Measured (seed 5), s after the hold, exponent 0 / 4: at 0.5 w 0.980 /
// 0.997; at 3 w 1.0009 / 1.0007.
TEST(FilterScaleHold, HalfTheWidthDoesNotTeachTheScale) {
  EXPECT_GT(std::abs(ScaleAfterHold(0.0, 0.5) - 1.0), 0.01);
  EXPECT_LT(std::abs(ScaleAfterHold(FilterOptions().scale_hold_exponent, 0.5) - 1.0), 0.005);
}

TEST(FilterScaleHold, ThreeWidthsStillTeachIt) {
  EXPECT_NEAR(ScaleAfterHold(FilterOptions().scale_hold_exponent, 3.0), 1.0, 0.002);
}

// A known defect, kept as the next fix's target (run with
// --gtest_also_run_disabled_tests): held at w to 1.2 w, s falls to 0.63–0.71
// whatever the exponent (exponent 0 / 4 — w: 0.666 / 0.706, 1.2 w: 0.634 /
// 0.682, 0.8 w: 0.928 / 0.912, 1.5 w: 0.924 / 0.927, 2 w: 0.98). It is the
// EKF's errors-in-variables bias on the bilinear term s·K·tau: the encoder's
// ∂h/∂s is K·tau at the estimated load, whose error is also in the innovation,
// so the gain on s correlates with the innovation and s is pulled toward 0
// at a rate ∝ σ_tau² (the tests below; docs/validation.md, Part 4, "The
// steady-hold drift of the compliance scale").
TEST(FilterScaleHold, DISABLED_AtTheWidthTheScaleHolds) {
  EXPECT_NEAR(ScaleAfterHold(FilterOptions().scale_hold_exponent, 1.0), 1.0, 0.05);
}

// The cause, pinned: without effort noise the same hold leaves s where the
// ramp put it (measured 0.93454 → 0.93442 from 1 s to 3.5 s); with the
// filter's own noise it falls 0.890 → 0.706 over the same 2.5 s.
TEST(FilterScaleHold, WithoutEffortNoiseASteadyHoldDoesNotMoveTheScale) {
  const double exponent = FilterOptions().scale_hold_exponent;
  const ScaleTrace quiet = TraceScaleOverHold(exponent, 1.0, 3.0, 0.0);
  EXPECT_NEAR(quiet.at_end, quiet.after_1s, 0.002);
  const ScaleTrace noisy = TraceScaleOverHold(exponent, 1.0, 3.0, 1.0);
  EXPECT_LT(noisy.at_end, noisy.after_1s - 0.1);
}

// The drift falls with the load (its rate is ∝ (σ_tau/tau)² and s is pinned
// tighter by a longer ramp): over 19 s held at 3 w, s stays within 0.015 of
// the truth (measured 0.9926; at 2 w 0.926, at 1.5 w 0.650).
TEST(FilterScaleHold, ALongHoldAtThreeWidthsKeepsTheScale) {
  EXPECT_NEAR(TraceScaleOverHold(FilterOptions().scale_hold_exponent, 3.0, 19.0, 1.0).at_end, 1.0,
              0.015);
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
