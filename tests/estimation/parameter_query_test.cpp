#include "pliant/estimation/parameter_query.h"

#include <gtest/gtest.h>

#include "paper_parameters.h"

namespace pliant::estimation {
namespace {

TEST(ParameterQuery, PropagatesTheLawCovarianceToK) {
  models::ModelParameters p = models::testing::PaperParameters();
  // Only c0 of joint 1 uncertain (sd 0.5 N·m/rad): sd(1/K) = 0.5, sd(K) = 0.5·K².
  p.covariance = models::ParameterCovariance{
      {"joint1.compliance.c0", "joint2.backlash_rad"}, Eigen::Matrix2d{{0.25, 0.0}, {0.0, 1e-8}}};
  const auto at = QueryParametersAtDepth(p, 0.15);
  const double k1 = 1.0 / 15.99729;
  EXPECT_NEAR(at.joints[0].compliance_rad_per_nm, k1, 1e-12);
  EXPECT_NEAR(at.joints[0].compliance_sd, 0.5 * k1 * k1, 1e-12);
  EXPECT_NEAR(at.joints[0].inverse_compliance_sd, 0.5, 1e-12);
  EXPECT_EQ(at.joints[1].compliance_sd, 0.0);
  EXPECT_NEAR(at.joints[1].backlash_sd, 1e-4, 1e-15);
  EXPECT_FALSE(at.joints[0].depth_clamped);
  EXPECT_TRUE(QueryParametersAtDepth(p, 0.25).joints[0].depth_clamped);
}

TEST(ParameterQuery, EvaluatesTheBeamSeriesLaw) {
  models::ModelParameters p = models::testing::PaperParameters();
  p.joints[0].compliance = {models::ComplianceForm::kBeamSeries, {{0.03, 0.004, 0.8, 0.025}}};
  // 0.03 + 0.004/0.12 + 0.8·0.095³/(3·0.12²)
  const double expected = 0.03 + 0.004 / 0.12 + 0.8 * 0.095 * 0.095 * 0.095 / (3 * 0.0144);
  EXPECT_NEAR(QueryParametersAtDepth(p, 0.12).joints[0].compliance_rad_per_nm, expected, 1e-15);
}

}  // namespace
}  // namespace pliant::estimation
