// The effort drift r·(1 − e^(−kt))/k per joint, against closed forms: the
// first-order settling, its linear limit k → 0 (inside the parameter space),
// and its derivatives there, which the fits read through autodiff.
#include "pliant/models/effects/effort_drift.h"

#include <gtest/gtest.h>

#include <cmath>

#include <ceres/jet.h>

namespace pliant::models {
namespace {

JointState<double> At(double time_s) {
  JointState<double> s;
  s.time_s = time_s;
  return s;
}

// rate1, rate2 (N·m/s), settling_rate (1/s).
TEST(EffortDrift, SettlesAtTheRateOverTheSettlingRate) {
  const double p[3] = {0.002, -0.001, 0.05};
  for (double t : {0.0, 5.0, 20.0, 300.0}) {
    const Vec2<double> d = EffortDriftEffect{}(p, At(t));
    EXPECT_NEAR(d[0], 0.002 / 0.05 * (1.0 - std::exp(-0.05 * t)), 1e-15) << t;
    EXPECT_NEAR(d[1], -0.001 / 0.05 * (1.0 - std::exp(-0.05 * t)), 1e-15) << t;
  }
}

TEST(EffortDrift, AtZeroSettlingRateItIsALinearCreep) {
  const double linear[3] = {8e-4, 8e-4, 0.0};
  EXPECT_DOUBLE_EQ(EffortDriftEffect{}(linear, At(300.0))[0], 8e-4 * 300.0);
  // Continuous across the switch to the series at k·t = 1e-6: the two sides
  // agree to the series' next term, (kt)²/6 relative.
  const double below[3] = {1.0, 1.0, 0.99e-6 / 100.0}, above[3] = {1.0, 1.0, 1.01e-6 / 100.0};
  const double exact_below = -std::expm1(-0.99e-6) / below[2];
  const double exact_above = -std::expm1(-1.01e-6) / above[2];
  EXPECT_NEAR(EffortDriftEffect{}(below, At(100.0))[0], exact_below, 1e-12 * exact_below);
  EXPECT_NEAR(EffortDriftEffect{}(above, At(100.0))[0], exact_above, 1e-12 * exact_above);
}

// d/dk of r·(1 − e^(−kt))/k at k = 0 is −r·t²/2: a fit started at a linear
// creep sees which way curvature would go.
TEST(EffortDrift, TheSettlingRatesDerivativeAtTheLinearLimitIsMinusRTSquaredOverTwo) {
  using Jet = ceres::Jet<double, 1>;
  const Jet p[3] = {Jet(0.001), Jet(0.001), Jet(0.0, 0)};
  JointState<Jet> s;
  s.time_s = Jet(200.0);
  const Vec2<Jet> d = EffortDriftEffect{}(p, s);
  EXPECT_NEAR(d[0].v[0], -0.001 * 200.0 * 200.0 / 2.0, 1e-12);
}

}  // namespace
}  // namespace pliant::models
