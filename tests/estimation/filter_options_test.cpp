// The filter's options and its motor-motion tracker (J·θ̈) against closed
// forms; the filter itself: filter_test.cpp.
#include "pliant/estimation/filter.h"

#include <cmath>
#include <string>

#include <Eigen/Cholesky>
#include <gtest/gtest.h>


namespace pliant::estimation {
namespace {

TEST(FilterOptions, DefaultsAreValid) {
  std::string error;
  EXPECT_TRUE(FilterOptions{}.IsValid(&error)) << error;
}

TEST(FilterOptions, NamesTheWrongOptionAndTheFix) {
  FilterOptions o;
  o.effort_noise_nm = 0.0;
  std::string error;
  EXPECT_FALSE(o.IsValid(&error));
  EXPECT_EQ(error, "FilterOptions::effort_noise_nm = 0.000000 must be finite and > 0 — give it in N·m");
  o = FilterOptions{};
  o.gate_probability = 1.0;
  EXPECT_FALSE(o.IsValid(&error));
  EXPECT_NE(error.find("gate_probability"), std::string::npos) << error;
  o = FilterOptions{};
  o.mismatch_window = 3;
  EXPECT_FALSE(o.IsValid(&error));
  EXPECT_NE(error.find("mismatch_window"), std::string::npos) << error;
}

TEST(FilterOptions, RefusesNegativeModelErrorsAndInertia) {
  std::string error;
  FilterOptions o;
  o.deflection_model_error = -0.1;
  EXPECT_FALSE(o.IsValid(&error));
  EXPECT_NE(error.find("deflection_model_error"), std::string::npos) << error;
  o = FilterOptions{};
  o.motor_inertia_kg_m2 = std::nan("");
  EXPECT_FALSE(o.IsValid(&error));
  EXPECT_NE(error.find("motor_inertia_kg_m2"), std::string::npos) << error;
}

// Under a constant acceleration a the encoder follows a·t²/2; once the
// tracker has settled (θ^k negligible after 75 T) the estimate is a and the
// velocity a·t, both without lag (the fit is exact on a quadratic), and the
// inertial torque J·a, never beyond the effort limit.
TEST(MotorMotion, RecoversAConstantAccelerationAndBoundsTheTorque) {
  FilterOptions o;
  o.motor_inertia_kg_m2 = 0.08;
  const double a = 1.5, dt = 1.0 / 1500.0;
  MotorMotion motion;
  double q_previous = 0.0;
  for (int k = 1; k <= 300; ++k) {  // 0.2 s = 50 T
    const double q = 0.5 * a * (k * dt) * (k * dt);
    motion.Advance(o, dt, q - q_previous);
    q_previous = q;
  }
  EXPECT_NEAR(motion.acceleration_rad_s2, a, 1e-6);
  EXPECT_NEAR(motion.velocity_rad_s, a * 300 * dt, 1e-8);
  EXPECT_NEAR(motion.InertialTorque(o), 0.08 * a, 1e-7);
  motion.acceleration_rad_s2 = 1e3;  // an encoder outlier's worth
  EXPECT_EQ(motion.InertialTorque(o), o.effort_limit_nm);
}

// The lag under a constant jerk j (q = j·t³/6, θ̈ = j·t), checked against a
// closed form independent of the recursion: in steady state the fading-memory
// filter is the quadratic c0 + c1·τ + c2·τ² fitted to the samples τ_k = −k·dt
// by least squares with weights θ^k. With τ in samples and q = (j·dt³/6)·τ³,
// the fit's acceleration at the newest sample is 2·c2·j·dt/6 (c2 from fitting
// τ³) where the truth is 0, so the estimate lags by L = −c2·dt/3; c2 comes
// from the weighted moments S_m = Σ θ^k k^m (m = 0..5), a 3×3 solve. With the
// default T = 4 ms, L ≈ 2.9 T ≈ 11.6 ms against the two 10 ms low-pass stages'
// 2 × 10 ms = 20 ms.
TEST(MotorMotion, LagUnderAConstantJerkIsTheFadingMemoryFitsAndShorterThanBefore) {
  FilterOptions o;
  const double dt = 1.0 / 1500.0, j = 3.0;
  const double theta = std::exp(-dt / o.acceleration_filter_time_s);
  double S[6] = {};
  double w = 1.0;
  for (int k = 0; k < 20000; ++k, w *= theta) {
    for (int m = 0; m < 6; ++m) S[m] += w * std::pow(double(k), m);
  }
  // Normal equations in the basis 1, τ, τ² with τ = −k (units of dt); the
  // right-hand side is the weighted projection of τ³.
  Eigen::Matrix3d normal;
  normal << S[0], -S[1], S[2], -S[1], S[2], -S[3], S[2], -S[3], S[4];
  const Eigen::Vector3d rhs(-S[3], S[4], -S[5]);
  const Eigen::Vector3d c = normal.ldlt().solve(rhs);
  const double expected_lag_s = -c[2] * dt / 3.0;
  MotorMotion motion;
  double q_previous = 0.0;
  const int steps = 1500;  // 1 s = 250 T
  for (int k = 1; k <= steps; ++k) {
    const double t = k * dt;
    const double q = j * t * t * t / 6.0;
    motion.Advance(o, dt, q - q_previous);
    q_previous = q;
  }
  const double lag_s = (j * steps * dt - motion.acceleration_rad_s2) / j;
  EXPECT_NEAR(lag_s, expected_lag_s, 1e-9);
  EXPECT_NEAR(lag_s, 2.9 * o.acceleration_filter_time_s, 0.1 * o.acceleration_filter_time_s);
  EXPECT_LT(lag_s, 0.65 * 2.0 * 0.01);  // the old estimator: 2 × 10 ms
}

// Quantised to the encoder's count (7.7 µrad at 1.5 kHz), a constant
// acceleration is recovered on average to within 0.2 % once settled, and no
// sample strays by more than about two counts' flicker (one count moves θ̈ by
// 2·g_a·count/dt² ≈ 0.06 rad/s² at T = 4 ms; measured worst 0.07 rad/s²).
TEST(MotorMotion, RecoversAQuantisedConstantAcceleration) {
  FilterOptions o;
  const double a = 2.0, dt = 1.0 / 1500.0, count = 7.7e-6;
  MotorMotion motion;
  double q_previous = 0.0, sum = 0.0, worst = 0.0;
  int n = 0;
  for (int k = 1; k <= 1500; ++k) {
    const double t = k * dt;
    const double q = count * std::round(0.5 * a * t * t / count);
    motion.Advance(o, dt, q - q_previous);
    q_previous = q;
    if (k > 300) {  // 0.2 s = 50 T
      sum += motion.acceleration_rad_s2;
      worst = std::max(worst, std::abs(motion.acceleration_rad_s2 - a));
      ++n;
    }
  }
  EXPECT_NEAR(sum / n, a, 0.002 * a);
  EXPECT_LT(worst, 0.15);
}

}  // namespace
}  // namespace pliant::estimation
