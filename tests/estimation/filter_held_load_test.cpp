// A held tip's load moves only as the motor bends the shaft
// (FilterOptions::bound_held_load_rate, HeldLoadProcessVariance): the closed
// form of its process variance, and what the bound does to the compliance
// scale through a long steady hold (tests/support/steady_hold.h); the load
// a held tip's motor adds, and the inertial torque's share of the effort noise.
#include <cmath>
#include <limits>
#include <string>

#include <ceres/jet.h>
#include <gtest/gtest.h>

#include "../support/steady_hold.h"
#include "pliant/estimation/filter.h"

namespace pliant::estimation {
namespace {

using testing::TraceScaleOverHold;

constexpr double kDt = 1.0 / 1500.0;

TEST(HeldLoadProcessVariance, OnTheWallAtRestIsTheRestRate) {
  const FilterOptions o;
  EXPECT_DOUBLE_EQ(HeldLoadProcessVariance(o, kDt, 0.0, 0.05, 0.0, 1.0), 0.01 * 0.01 * kDt);
}

// One count (7.7 µrad) at s·K = 0.05 rad/N·m with a margin of 2 may add
// 3.08·10⁻⁴ N·m; 0.005 N·m of inertial torque adds 0.005²·dt/0.02 N·m².
TEST(HeldLoadProcessVariance, AddsWhatTheMotorCanBendAndTheInertialMisread) {
  const FilterOptions o;
  const double moved = 2.0 * 7.7e-6 / 0.05;
  const double bound = 1e-4 * kDt + moved * moved + 0.005 * 0.005 * kDt / 0.02;
  EXPECT_NEAR(HeldLoadProcessVariance(o, kDt, -7.7e-6, 0.05, 0.005, 1.0), bound, 1e-18);
  // Half held: halfway to the free rate σ_τ̇²·dt; off the wall: the free rate.
  const double free_rate = 0.1 * 0.1 * kDt;
  EXPECT_NEAR(HeldLoadProcessVariance(o, kDt, -7.7e-6, 0.05, 0.005, 0.5),
              0.5 * (bound + free_rate), 1e-18);
  EXPECT_DOUBLE_EQ(HeldLoadProcessVariance(o, kDt, -7.7e-6, 0.05, 0.005, 0.0), free_rate);
}

TEST(HeldLoadProcessVariance, NeverAboveTheFreeRate) {
  const FilterOptions o;
  const double free_rate = 0.1 * 0.1 * kDt;
  // 0.01 rad in one sample: a move no held shaft could take without this bound.
  EXPECT_DOUBLE_EQ(HeldLoadProcessVariance(o, kDt, 0.01, 0.05, 0.0, 1.0), free_rate);
  // A compliance of 0 (s driven to 0) is floored, not divided by.
  EXPECT_DOUBLE_EQ(HeldLoadProcessVariance(o, kDt, 7.7e-6, 0.0, 0.0, 1.0), free_rate);
  FilterOptions off;
  off.bound_held_load_rate = false;
  EXPECT_DOUBLE_EQ(HeldLoadProcessVariance(off, kDt, 0.0, 0.05, 0.0, 1.0), free_rate);
}

TEST(HeldLoadProcessVariance, OptionsAreValidated) {
  std::string error;
  FilterOptions o;
  o.held_load_rest_rate_nm = -1e-3;
  EXPECT_FALSE(o.IsValid(&error));
  EXPECT_NE(error.find("held_load_rest_rate_nm"), std::string::npos);
  o = FilterOptions();
  o.held_load_motion_margin = 0.5;
  EXPECT_FALSE(o.IsValid(&error));
  EXPECT_NE(error.find("held_load_motion_margin"), std::string::npos);
  o = FilterOptions();
  o.held_load_inertial_time_s = 0.0;
  EXPECT_FALSE(o.IsValid(&error));
  EXPECT_NE(error.find("held_load_inertial_time_s"), std::string::npos);
  o.held_load_inertial_time_s = 0.02;
  o.held_load_rest_rate_nm = 0.0;  // a load that never drifts at rest is a valid claim
  EXPECT_TRUE(o.IsValid(&error));
}

// The motor's increment bends a shaft held on its wall: 0.6 mrad at
// s·K = 1.1 × 0.06 rad/N·m is 0.6e-3 / 0.066 N·m; half held (g = 0.5), half of
// that; its ∂/∂s (the filter's F entry, by Jet) is −tau_added/s.
TEST(HeldLoadIncrement, IsTheBendOverTheComplianceAndItsScaleDerivative) {
  EXPECT_NEAR(HeldLoadIncrement(1.0, 6e-4, 1.1, 0.06), 6e-4 / 0.066, 1e-15);
  EXPECT_NEAR(HeldLoadIncrement(0.5, 6e-4, 1.1, 0.06), 0.5 * 6e-4 / 0.066, 1e-15);
  EXPECT_EQ(HeldLoadIncrement(0.0, 6e-4, 1.1, 0.06), 0.0);  // unloaded: the encoder moves b
  const ceres::Jet<double, 1> scale(1.1, 0);
  const auto added = HeldLoadIncrement(1.0, 6e-4, scale, 0.06);
  EXPECT_NEAR(added.v[0], -6e-4 / 0.066 / 1.1, 1e-15);
}

// The inertial torque's misread as effort variance: σ² + (κ·J·θ̈)².
TEST(HeldEffortVariance, AddsTheInertialTorquesShare) {
  FilterOptions o;
  o.effort_noise_nm = 0.01;
  o.inertial_torque_error = 0.3;
  EXPECT_NEAR(HeldEffortVariance(o, 0.0), 1e-4, 1e-18);
  EXPECT_NEAR(HeldEffortVariance(o, -0.1), 1e-4 + 0.03 * 0.03, 1e-18);
  o.inertial_torque_error = 0.0;
  EXPECT_NEAR(HeldEffortVariance(o, 0.1), 1e-4, 1e-18);
  std::string error;
  EXPECT_TRUE(o.IsValid(&error)) << error;
  o.inertial_torque_error = -0.3;
  EXPECT_FALSE(o.IsValid(&error));
  EXPECT_NE(error.find("inertial_torque_error"), std::string::npos);
  o.inertial_torque_error = std::numeric_limits<double>::quiet_NaN();
  EXPECT_FALSE(o.IsValid(&error));
}

// Joint 1 held 19 s at 1.5 w with the filter's effort noise (truth s = 1).
// Measured: bounded s 0.978, tip 97 counts off; with the load's rate free
// (σ_τ̇ alone) s 0.658, tip 393 counts off (build/bench/filter_steady_hold_bench).
TEST(FilterHeldLoad, ABoundedLoadKeepsTheScaleThroughALongHold) {
  FilterOptions on;
  on.infer_contact = false;  // the approach's free tip carries the load: all of it is load
  const auto bounded = TraceScaleOverHold(on, 1.5, 19.0, 1.0);
  FilterOptions off = on;
  off.bound_held_load_rate = false;
  const auto unbounded = TraceScaleOverHold(off, 1.5, 19.0, 1.0);
  EXPECT_NEAR(bounded.at_end, 1.0, 0.05);
  EXPECT_LT(unbounded.at_end, 0.8);
  EXPECT_LT(std::abs(bounded.tip_error_counts), 0.5 * std::abs(unbounded.tip_error_counts));
}

}  // namespace
}  // namespace pliant::estimation
