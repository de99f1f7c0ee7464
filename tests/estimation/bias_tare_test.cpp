#include "pliant/estimation/bias_tare.h"

#include <cmath>

#include <gtest/gtest.h>

#include "pliant/models/paper_parameters.h"

namespace pliant::estimation {
namespace {

const TareRows kRows{{0.1, 0.3, -0.2}, {0.12, 0.14, 0.10}};

TEST(BiasTare, ShiftsEveryTorqueOfATableAndSaysWhere) {
  auto p = models::PaperParameters();
  p.joints[0].sources["bias_torque"] = "a sweep";
  const auto before = p;
  TareBiasTorque(0, 0.07, 0.002, kRows, "tared on my.csv", &p);
  for (double q : {-1.0, 0.0, 0.4, 2.0}) {
    EXPECT_NEAR(models::BiasTorqueAt(p.joints[0], q, 0.15),
                models::BiasTorqueAt(before.joints[0], q, 0.15) + 0.07, 1e-15);
    EXPECT_EQ(models::BiasTorqueAt(p.joints[1], q, 0.15),
              models::BiasTorqueAt(before.joints[1], q, 0.15));
  }
  EXPECT_EQ(p.joints[0].sources["bias_torque"], "a sweep; tared on my.csv");
  EXPECT_EQ(BiasSdOver(p, 0, kRows), 0.0);  // a table carries no σ
}

// Joint 2 with a Fourier bias a0 + a1·cos q + b1·sin q + s·(L − 0.155) and a
// covariance over its four numbers and joint 2's backlash.
models::ModelParameters FourierParameters() {
  auto p = models::PaperParameters();
  auto& joint = p.joints[1];
  joint.bias_form = models::BiasForm::kFourier;
  joint.bias_fourier = {{-0.1, 0.03, -0.02}, 0.5, 0.155};
  models::ParameterCovariance c;
  c.names = {"joint2.bias_torque.coefficients[0]", "joint2.bias_torque.coefficients[1]",
             "joint2.bias_torque.coefficients[2]", "joint2.bias_torque.depth_slope_nm_per_m",
             "joint2.backlash_rad"};
  Eigen::MatrixXd l = Eigen::MatrixXd::Zero(5, 5);
  l << 0.02, 0, 0, 0, 0, 0.005, 0.01, 0, 0, 0, -0.003, 0.002, 0.008, 0, 0, 0.01, 0, 0.02, 0.1, 0,
      1e-4, 0, 0, 2e-5, 3e-4;
  c.matrix = l * l.transpose();
  p.covariance = c;
  return p;
}

// The mean over kRows of ∂tau0/∂(a0, a1, b1, s), written out.
Eigen::VectorXd Gradient() {
  Eigen::VectorXd g = Eigen::VectorXd::Zero(5);
  for (int r = 0; r < 3; ++r) {
    g[0] += 1.0 / 3.0;
    g[1] += std::cos(kRows.angle_rad[r]) / 3.0;
    g[2] += std::sin(kRows.angle_rad[r]) / 3.0;
    g[3] += (kRows.depth_m[r] - 0.155) / 3.0;
  }
  return g;
}

TEST(BiasTare, AFourierBiasMovesA0AndItsCovarianceFollows) {
  auto p = FourierParameters();
  const Eigen::MatrixXd sigma = p.covariance->matrix;
  const Eigen::VectorXd g = Gradient();
  EXPECT_NEAR(BiasSdOver(p, 1, kRows), std::sqrt(g.dot(sigma * g)), 1e-15);
  const double at = models::BiasTorqueAt(p.joints[1], 0.2, 0.13);
  TareBiasTorque(1, -0.04, 0.003, kRows, "tared on my.csv", &p);
  EXPECT_NEAR(models::BiasTorqueAt(p.joints[1], 0.2, 0.13), at - 0.04, 1e-15);
  EXPECT_DOUBLE_EQ(p.joints[1].bias_fourier.coefficients[0], -0.14);
  // a0' = mean(tau) − g1·a1 − g2·b1 − g3·s: its row of the covariance.
  Eigen::VectorXd row = Eigen::VectorXd::Zero(5);
  row.segment(1, 3) = -g.segment(1, 3);
  const auto& tared = p.covariance->matrix;
  EXPECT_NEAR(tared(0, 0), row.dot(sigma * row) + 0.003 * 0.003, 1e-15);
  for (int k = 1; k < 5; ++k) EXPECT_NEAR(tared(0, k), (sigma * row)[k], 1e-15);
  EXPECT_TRUE(tared.bottomRightCorner(4, 4).isApprox(sigma.bottomRightCorner(4, 4), 1e-15));
  // What the tare measured, tau0 averaged over its rows, is now known to the
  // tare's own σ: the parameters' earlier doubt about it is gone.
  EXPECT_NEAR(BiasSdOver(p, 1, kRows), 0.003, 1e-12);
}

// The depth harmonic (L − L_ref)·(c1·cos q + d1·sin q): its σ enters tau0's
// through the row means of (L − L_ref)·cos q and (L − L_ref)·sin q, and a
// tare moves a0 by minus those times c1, d1.
TEST(BiasTare, TheDepthHarmonicsCovarianceEntersTheBiasSd) {
  auto p = FourierParameters();
  p.joints[1].bias_fourier.depth_harmonic_nm_per_m = {0.4, -0.6};
  models::ParameterCovariance c;
  c.names = {"joint2.bias_torque.depth_harmonic_nm_per_m[0]",
             "joint2.bias_torque.depth_harmonic_nm_per_m[1]"};
  c.matrix.resize(2, 2);
  c.matrix << 0.09, -0.02, -0.02, 0.16;
  p.covariance = c;
  Eigen::Vector2d g = Eigen::Vector2d::Zero();
  for (int r = 0; r < 3; ++r) {
    const double lever = kRows.depth_m[r] - 0.155;
    g[0] += lever * std::cos(kRows.angle_rad[r]) / 3.0;
    g[1] += lever * std::sin(kRows.angle_rad[r]) / 3.0;
  }
  EXPECT_NEAR(BiasSdOver(p, 1, kRows), std::sqrt(g.dot(c.matrix * g)), 1e-15);
  TareBiasTorque(1, 0.0, 0.0, kRows, "tared on my.csv", &p);
  const auto& tared = *p.covariance;
  ASSERT_EQ(tared.names.size(), 3u);  // a0 added
  EXPECT_NEAR(tared.matrix(2, 2), g.dot(c.matrix * g), 1e-15);
  EXPECT_NEAR(BiasSdOver(p, 1, kRows), 0.0, 1e-12);
}

TEST(BiasTare, AFourierBiasWithoutCovarianceGetsA0sFromTheTare) {
  auto p = FourierParameters();
  p.covariance.reset();
  TareBiasTorque(1, 0.05, 0.004, kRows, "tared on my.csv", &p);
  ASSERT_TRUE(p.covariance.has_value());
  ASSERT_EQ(p.covariance->names.size(), 1u);
  EXPECT_EQ(p.covariance->names[0], "joint2.bias_torque.coefficients[0]");
  EXPECT_NEAR(p.covariance->matrix(0, 0), 0.004 * 0.004, 1e-18);
}

}  // namespace
}  // namespace pliant::estimation
