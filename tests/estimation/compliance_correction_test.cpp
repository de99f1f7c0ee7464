#include "pliant/estimation/compliance_correction.h"

#include <cmath>

#include <gtest/gtest.h>

#include "paper_parameters.h"

namespace pliant::estimation {
namespace {

// A hand-checkable instrument: no bias, K = 0.05 rad/(N·m) at every depth.
models::ModelParameters HandParameters() {
  models::ModelParameters p = models::testing::PaperParameters();
  for (auto& joint : p.joints) {
    joint.bias_torque = {{0.0}, {0.0}};
    joint.compliance.cubic.coefficients = {0.0, 0.0, 0.0, 20.0};
  }
  return p;
}

TEST(Equation2, CorrectsOnlyAboveTauMin) {
  const ComplianceCorrector paper(HandParameters(), CorrectionModel::kPaper);
  const Eigen::Vector3d q(0.1, -0.2, 0.15);
  // Joint 1: tau_min 0.1. Just under, at (strict >: no correction) and over.
  EXPECT_EQ(paper.Correct(q, {0.0999, 0.0}).corrected_rad[0], 0.1);
  EXPECT_EQ(paper.Correct(q, {0.1, 0.0}).corrected_rad[0], 0.1);
  EXPECT_NEAR(paper.Correct(q, {0.1001, 0.0}).corrected_rad[0], 0.1 - 0.008478 - 0.05 * 0.1001,
              1e-15);
  EXPECT_NEAR(paper.Correct(q, {-1.0, 0.0}).corrected_rad[0], 0.1 + 0.008478 + 0.05, 1e-15);
  // Joint 2: tau_min 0.2.
  EXPECT_EQ(paper.Correct(q, {0.0, -0.1999}).corrected_rad[1], -0.2);
  EXPECT_EQ(paper.Correct(q, {0.0, -0.2}).corrected_rad[1], -0.2);
  EXPECT_NEAR(paper.Correct(q, {0.0, -0.2001}).corrected_rad[1], -0.2 + 0.007176 + 0.05 * 0.2001,
              1e-15);
}

TEST(Equation2, SubtractsTheBiasTorqueFirst) {
  models::ModelParameters p = HandParameters();
  p.joints[0].bias_torque = {{-1.0, 1.0}, {0.1, 0.3}};  // tau0 = 0.2 + 0.1·q1
  const ComplianceCorrector paper(p, CorrectionModel::kPaper);
  const auto c = paper.Correct({0.0, 0.0, 0.15}, {0.25, 0.0});  // tau_ext = 0.05 < tau_min
  EXPECT_NEAR(c.external_torque_nm[0], 0.05, 1e-15);
  EXPECT_EQ(c.corrected_rad[0], 0.0);
  const auto loaded = paper.Correct({0.0, 0.0, 0.15}, {1.2, 0.0});  // tau_ext = 1.0
  EXPECT_NEAR(loaded.corrected_rad[0], -(0.008478 + 0.05 * 1.0), 1e-15);
}

// Fourier biases with depth harmonics and different reference depths: the
// corrector puts both joints on one reference depth and one harmonic count
// (joint 1 has only a0), and its tau_ext is tau − BiasTorqueAt at every pose.
TEST(Equation2, SubtractsAFourierBiasWithItsDepthHarmonic) {
  models::ModelParameters p = HandParameters();
  p.joints[0].bias_form = p.joints[1].bias_form = models::BiasForm::kFourier;
  p.joints[0].bias_fourier = {{0.12}, 0.3, 0.155, {0.4, -0.7}};
  p.joints[1].bias_fourier = {{-0.05, 0.02, 0.11, 0.01, -0.004}, -0.24, 0.10, {-0.2, 0.5}};
  const ComplianceCorrector deadzone(p, CorrectionModel::kDeadZone);
  for (const Eigen::Vector3d q : {Eigen::Vector3d(0.3, -0.4, 0.09), Eigen::Vector3d(-0.8, 0.6, 0.21),
                                  Eigen::Vector3d(1.2, 0.1, 0.155)}) {
    const Eigen::Vector2d tau(0.5, -0.3);
    const auto c = deadzone.Correct(q, tau);
    for (int j = 0; j < 2; ++j) {
      EXPECT_NEAR(c.external_torque_nm[j], tau[j] - models::BiasTorqueAt(p.joints[j], q[j], q[2]),
                  1e-14);
    }
  }
  // Joint 1 at q = 0.3, L = 0.21: 0.12 + 0.055·(0.3 + 0.4·cos 0.3 − 0.7·sin 0.3), by hand.
  EXPECT_NEAR(deadzone.Correct({0.3, 0.0, 0.21}, {0.0, 0.0}).external_torque_nm[0],
              -(0.12 + 0.055 * (0.3 + 0.4 * std::cos(0.3) - 0.7 * std::sin(0.3))), 1e-14);
}

TEST(Equation2, UsesThePapersKAtTheDepth) {
  const ComplianceCorrector paper(models::testing::PaperParameters(), CorrectionModel::kPaper);
  const auto c = paper.Correct({0.0, 0.0, 0.15}, {0.199 + 1.0, -0.0029145 - 1.0});
  EXPECT_NEAR(c.deflection_rad[0], 0.008478 + 1.0 / 15.99729, 1e-12);
  EXPECT_NEAR(c.deflection_rad[1], -0.007176 - 1.0 / 27.70782375, 1e-12);
  EXPECT_FALSE(c.depth_clamped);
  EXPECT_TRUE(paper.Correct({0.0, 0.0, 0.05}, {0.0, 0.0}).depth_clamped);
}

TEST(Equation2, JumpsByDeltaPlusKTauMinAtTheThreshold) {
  const ComplianceCorrector paper(models::testing::PaperParameters(), CorrectionModel::kPaper);
  const double eps = 1e-9;
  const Eigen::Vector3d q(0.0, 0.0, 0.15);
  const double below = paper.Correct(q, {0.199 + 0.1 - eps, 0.0}).corrected_rad[0];
  const double above = paper.Correct(q, {0.199 + 0.1 + eps, 0.0}).corrected_rad[0];
  const double jump = 0.008478 + 0.1 / 15.99729;  // 14.73 mrad: about 2 mm at the tip
  EXPECT_NEAR(below - above, jump, 1e-8);
  EXPECT_NEAR(paper.JumpAtThreshold(0, 0.15), jump, 1e-12);
}

TEST(DeadZone, IsContinuousAcrossTauMin) {
  const ComplianceCorrector deadzone(models::testing::PaperParameters(),
                                     CorrectionModel::kDeadZone);
  const Eigen::Vector3d q(0.0, 0.0, 0.15);
  // Sweep tau_ext through ±2·tau_min in small steps: the corrected angle never
  // moves by more than its Lipschitz bound δ·S'(0)/w·dτ + K·dτ per step.
  const double step = 1e-4;
  const double bound = (0.008478 * 15.0 / 8.0 / 0.1 + 1.0 / 15.99729) * step;
  double previous = deadzone.Correct(q, {0.199 - 0.2, 0.0}).corrected_rad[0];
  for (double tau = -0.2 + step; tau <= 0.2; tau += step) {
    const double current = deadzone.Correct(q, {0.199 + tau, 0.0}).corrected_rad[0];
    ASSERT_LE(std::abs(current - previous), bound * (1 + 1e-9)) << "at tau_ext " << tau;
    previous = current;
  }
  EXPECT_EQ(deadzone.JumpAtThreshold(0, 0.15), 0.0);
}

TEST(DeadZone, AgreesWithEquation2UnderFullLoad) {
  const auto p = models::testing::PaperParameters();
  const ComplianceCorrector paper(p, CorrectionModel::kPaper);
  const ComplianceCorrector deadzone(p, CorrectionModel::kDeadZone);
  for (double tau : {-1.5, -0.6, 0.3, 1.0}) {
    const Eigen::Vector3d q(0.2, -0.1, 0.12);
    const Eigen::Vector2d torque(0.199 + tau, -0.0029145 - tau);
    EXPECT_NEAR((paper.Correct(q, torque).corrected_rad -
                 deadzone.Correct(q, torque).corrected_rad).norm(), 0.0, 1e-15);
  }
}

TEST(ComplianceCorrector, RejectsInvalidParameters) {
  models::ModelParameters p = models::testing::PaperParameters();
  p.joints[1].depth_min_m = 0.01;
  try {
    ComplianceCorrector bad(p, CorrectionModel::kPaper);
    FAIL() << "accepted 1/K2 <= 0 inside the depth range";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("joint2: the compliance cubic reaches"),
              std::string::npos);
  }
}

TEST(ParseCorrectionModel, KnowsTwoNames) {
  EXPECT_EQ(ParseCorrectionModel("paper"), CorrectionModel::kPaper);
  EXPECT_EQ(ParseCorrectionModel("deadzone"), CorrectionModel::kDeadZone);
  EXPECT_FALSE(ParseCorrectionModel("Paper").has_value());
}

}  // namespace
}  // namespace pliant::estimation
