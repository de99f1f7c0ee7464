// The free level (filter_free_level.h, docs/decisions/contact-free-level.md):
// the field's prediction in closed form, a lesson the field cannot have made
// refused, and what it buys online: a light push after a rest, at a pose
// whose bias-table error the filter does not know.
#include <algorithm>
#include <cmath>
#include <random>
#include <string>

#include <gtest/gtest.h>

#include "../../estimation/src/filter_free_level.h"
#include "../support/paper_parameters.h"
#include "../support/pushed_tip.h"
#include "pliant/estimation/compliance_correction.h"
#include "pliant/estimation/filter.h"

namespace pliant::estimation {
namespace {

using filter_internal::FreeLevel;

// Taught at one pose, the level elsewhere is the squared-exponential field's
// conditional: mean ρ·m₀, variance ρ²·v₀ + (1 − ρ²)·E + σ_d²·Δt, with
// ρ = exp(−½ Σ (Δx_k / L_k)²) over both joints' angles and the depth.
TEST(FreeLevel, AwayFromWhereItWasTaughtIsTheFieldsConditional) {
  FilterOptions o;
  o.free_level_drift_nm = 0.003;
  const double equilibrium = 0.0125;
  FreeLevel level;
  level.Start(o, equilibrium);
  EXPECT_EQ(level.mean, 0.0);
  EXPECT_EQ(level.variance, equilibrium);
  const Eigen::Vector3d taught(0.2, -0.1, 0.15);
  level.Predict(taught, 0.01, 1.0, equilibrium);
  level.Teach(0.04, taught, 1.0, equilibrium);
  const double m0 = level.mean, v0 = level.variance;
  ASSERT_GT(m0, 0.03);  // a lesson at the field's own scale is taken
  ASSERT_LT(v0, 2.0 * o.effort_noise_nm * o.effort_noise_nm);
  const Eigen::Vector3d away(0.25, -0.02, 0.16);
  level.Predict(away, 0.5, 1.0, equilibrium);
  const double u2 = std::pow(0.05 / o.free_level_length_rad, 2) +
                    std::pow(0.08 / o.free_level_length_rad, 2) +
                    std::pow(0.01 / o.free_level_depth_length_m, 2);
  const double rho = std::exp(-0.5 * u2);
  EXPECT_NEAR(level.mean, rho * m0, 1e-15);
  EXPECT_NEAR(level.variance,
              rho * rho * v0 + (1.0 - rho * rho) * equilibrium + 0.003 * 0.003 * 0.5, 1e-15);
  // Back where it was taught, only the drift is new.
  level.Predict(taught, 0.5, 1.0, equilibrium);
  EXPECT_NEAR(level.mean, m0, 1e-15);
  EXPECT_NEAR(level.variance, v0 + 0.003 * 0.003 * 1.0, 1e-15);
  // A moving arm gets the field's prior: the level is a settled arm's.
  level.Predict(taught, 0.0, 0.0, equilibrium);
  EXPECT_EQ(level.Torque(), 0.0);
  EXPECT_NEAR(level.Variance(equilibrium), equilibrium, 1e-15);
}

// Once the level is known to a few mN·m, a lesson 0.3 N·m away is a load's,
// not the field's, and leaves it; one within the effort's noise is taken. A
// row without a depth leaves the pose where it was; off, nothing moves.
TEST(FreeLevel, ALessonTheFieldCannotHaveMadeIsRefused) {
  FilterOptions o;
  const double equilibrium = 0.0125;
  FreeLevel level;
  level.Start(o, equilibrium);
  const Eigen::Vector3d pose(0.0, 0.0, 0.12);
  for (int k = 0; k < 20; ++k) {
    level.Predict(pose, 0.05, 1.0, equilibrium);
    level.Teach(0.02, pose, 1.0, equilibrium);
  }
  const double known = level.mean;
  EXPECT_NEAR(known, 0.02, 1e-3);
  level.Teach(0.32, pose, 1.0, equilibrium);
  EXPECT_NEAR(level.mean, known, 1e-3);
  level.Teach(known + o.effort_noise_nm, pose, 1.0, equilibrium);
  EXPECT_GT(level.mean, known + 0.02 * o.effort_noise_nm);
  const double before = level.mean;
  level.Predict(Eigen::Vector3d(0.0, 0.0, std::nan("")), 0.0, 1.0, equilibrium);
  EXPECT_EQ(level.mean, before);

  o.free_level = false;
  FreeLevel off;
  off.Start(o, equilibrium);
  off.Predict(pose, 0.05, 1.0, equilibrium);
  off.Teach(0.02, pose, 1.0, equilibrium);
  EXPECT_FALSE(off.on);
  EXPECT_EQ(off.mean, 0.0);
}

// 100 Hz, no hint: the arm rests 1 s at a pose where the bias table misses
// `table_error_nm` on both joints (the filter is not told), then a light
// load (0.3 N·m, mostly joint 2) grows over 0.5 s and holds 1.5 s.
struct RestThenPush {
  double recognised_s = 1e9;   // first p > 0.5 after the push starts
  double held_rms_rad = 0.0;   // joint 2 over the hold (the load's last 1.5 s)
  double equation2_rms_rad = 0.0;
};

RestThenPush LightPushAfterARest(bool free_level, double table_error_nm, unsigned seed) {
  const auto p = models::testing::PaperParameters();
  FilterOptions o;
  o.free_level = free_level;
  std::mt19937_64 rng(seed);
  std::normal_distribution<double> normal(0.0, 1.0);
  ComplianceFilter filter(p, o);
  const ComplianceCorrector equation2(p, CorrectionModel::kPaper);
  const double depth = 0.15, rate = 100.0;
  const Eigen::Vector2d direction(std::sin(0.35), std::cos(0.35)), tip(0.1, -0.2);
  Eigen::Vector2d backlash = Eigen::Vector2d::Zero();
  RestThenPush out;
  int held = 0;
  for (int k = 0; k < 300; ++k) {
    const double t = k / rate;
    const double share = std::clamp((t - 1.0) / 0.5, 0.0, 1.0);
    const Eigen::Vector2d load = 0.3 * share * direction;
    const FilterSample s = testing::PushedTipSample(p, o, t, depth, tip, load, table_error_nm,
                                                    &backlash, &rng, &normal);
    const FilterEstimate e = filter.Step(s);
    if (t >= 1.0 && e.contact_probability[1] > 0.5) out.recognised_s = std::min(out.recognised_s, t - 1.0);
    if (t >= 1.5) {
      const Eigen::Vector3d q(s.encoder_rad[0], s.encoder_rad[1], depth);
      out.held_rms_rad += std::pow(e.corrected_rad[1] - tip[1], 2);
      out.equation2_rms_rad += std::pow(equation2.Correct(q, s.effort_nm).corrected_rad[1] - tip[1], 2);
      ++held;
    }
  }
  out.held_rms_rad = std::sqrt(out.held_rms_rad / held);
  out.equation2_rms_rad = std::sqrt(out.equation2_rms_rad / held);
  return out;
}

// Measured (seeds 1-3, table error −0.06 / 0 / +0.06 N·m): with the level
// the push is believed 0.54-0.55 s in (at 0.3 N·m) and joint 2 holds within
// 2.8-3.3 mrad RMS; without it, at −0.06 and 0 never (17 mrad: the tip
// follows the encoder), at +0.06 after 0.92-0.94 s (9.1-9.2 mrad). Equation
// (2), which reads the table as exact, 2.2-2.9 with the error and 0.35
// without: what is left is the load's climb once believed.
TEST(FreeLevel, ALightPushAfterARestIsToldFromTheTablesErrorByItsChange) {
  for (double table_error : {-0.06, 0.0, 0.06}) {
    for (unsigned seed = 1; seed <= 3; ++seed) {
      const RestThenPush with = LightPushAfterARest(true, table_error, seed);
      const RestThenPush without = LightPushAfterARest(false, table_error, seed);
      const std::string what =
          "table error " + std::to_string(table_error) + " N·m, seed " + std::to_string(seed);
      EXPECT_LT(with.recognised_s, 0.6) << what;
      EXPECT_LT(with.recognised_s, without.recognised_s) << what;
      EXPECT_LT(with.held_rms_rad, 4e-3) << what;
      EXPECT_LT(with.held_rms_rad, 0.5 * without.held_rms_rad) << what;
    }
  }
}

}  // namespace
}  // namespace pliant::estimation
