#include "pliant/experiments/quasi_static_push.h"

#include <cmath>

#include <gtest/gtest.h>

#include "paper_parameters.h"
#include "pliant/estimation/compliance_correction.h"

namespace pliant::experiments {
namespace {

struct Columns {
  explicit Columns(const io::Log& log) : c(log.header) {}
  io::StandardColumns c;
};

TEST(QuasiStaticPush, EncoderMinusTruthIsBacklashPlusBending) {
  PushScenario scenario = DefaultDivotScenario(models::testing::PaperParameters());
  scenario.effort_noise_sd_nm = 0.0;
  scenario.encoder_count_rad = 1e-12;  // no visible quantisation
  const io::Log log = GenerateDivotPushLog(scenario);
  const io::StandardColumns c(log.header);
  const auto& truth = scenario.truth;
  int checked = 0;
  for (std::size_t row = 0; row < log.Rows(); ++row) {
    const double tau_ext = log.Value(row, c.tau1) - 0.199;  // joint 1's flat bias
    if (std::abs(tau_ext) < 0.5) continue;  // well onto the cannula wall
    const double depth = log.Value(row, c.q3);
    const double expected = std::copysign(truth.joints[0].backlash_rad, tau_ext) +
                            models::ComplianceAt(truth.joints[0], depth) * tau_ext;
    ASSERT_NEAR(log.Value(row, c.q1) - log.Value(row, c.q1_true), expected, 1e-9) << row;
    ++checked;
  }
  EXPECT_GT(checked, 500);
}

TEST(QuasiStaticPush, BacklashHasHysteresisAtLowLoad) {
  // While the load ramps down through zero the shaft stays on the wall it was
  // pushed to: at near-zero load the encoder still reads ±delta off the truth.
  PushScenario scenario = DefaultDivotScenario(models::testing::PaperParameters());
  scenario.effort_noise_sd_nm = 0.0;
  const io::Log log = GenerateDivotPushLog(scenario);
  const io::StandardColumns c(log.header);
  std::size_t row = log.Rows() - 1;  // end of the last push: load back to zero
  EXPECT_NEAR(std::abs(log.Value(row, c.q1) - log.Value(row, c.q1_true)), 0.008478, 1e-5);
}

TEST(QuasiStaticPush, PaperCorrectionRemovesMostOfTheErrorUnderLoad) {
  const auto parameters = models::testing::PaperParameters();
  const io::Log log = GenerateDivotPushLog(DefaultDivotScenario(parameters));
  const io::StandardColumns c(log.header);
  const estimation::ComplianceCorrector paper(parameters, estimation::CorrectionModel::kPaper);
  double worst_corrected = 0.0, worst_uncorrected = 0.0;
  for (std::size_t row = 0; row < log.Rows(); ++row) {
    const Eigen::Vector3d q(log.Value(row, c.q1), log.Value(row, c.q2), log.Value(row, c.q3));
    const auto result = paper.Correct(q, {log.Value(row, c.tau1), log.Value(row, c.tau2)});
    if (result.external_torque_nm.cwiseAbs().minCoeff() < 0.5) continue;  // both joints loaded
    const Eigen::Vector2d truth(log.Value(row, c.q1_true), log.Value(row, c.q2_true));
    worst_corrected = std::max(worst_corrected, (result.corrected_rad - truth).cwiseAbs().maxCoeff());
    worst_uncorrected = std::max(worst_uncorrected, (q.head<2>() - truth).cwiseAbs().maxCoeff());
  }
  // Effort noise 0.01 N·m times K ≤ 0.081 rad/(N·m), 4σ, plus one encoder count.
  EXPECT_LT(worst_corrected, 4 * 0.01 * 0.081 + 7.7e-6);
  EXPECT_GT(worst_uncorrected, 0.03);
}

TEST(QuasiStaticPush, IsDeterministicForASeed) {
  const auto scenario = DefaultDivotScenario(models::testing::PaperParameters());
  EXPECT_EQ(GenerateDivotPushLog(scenario).values, GenerateDivotPushLog(scenario).values);
  auto other = scenario;
  other.seed = 2;
  EXPECT_NE(GenerateDivotPushLog(scenario).values, GenerateDivotPushLog(other).values);
}

}  // namespace
}  // namespace pliant::experiments
