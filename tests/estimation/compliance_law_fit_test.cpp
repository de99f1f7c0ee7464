#include "pliant/estimation/compliance_law_fit.h"

#include <cmath>
#include <stdexcept>

#include <gtest/gtest.h>

namespace pliant::estimation {
namespace {

using models::ComplianceForm;

// Exact points of a law at 14 depths, sd a fraction of 1/K.
std::vector<DepthCompliance> PointsOf(ComplianceForm form, std::array<double, 4> c,
                                      double relative_sd = 0.01) {
  std::vector<DepthCompliance> points;
  for (int i = 0; i < 14; ++i) {
    const double depth = 0.09 + 0.01 * i;
    const double inverse_k = 1.0 / models::EvaluateCompliance(form, c.data(), depth);
    points.push_back({depth, inverse_k, relative_sd * inverse_k});
  }
  return points;
}

TEST(ComplianceLawFit, RecoversEachLawFromItsOwnPoints) {
  const std::array<double, 4> paper{639.16, -432.35, 136.32, 3.12};
  const std::array<double, 4> dvrk{-38.3402, 22.6, -4.5406, 0.3458};
  const std::array<double, 4> beam{0.03, 0.004, 0.8, 0.025};
  for (auto [form, c] : {std::pair{ComplianceForm::kInverseCubic, paper},
                         std::pair{ComplianceForm::kDirectCubic, dvrk},
                         std::pair{ComplianceForm::kBeamSeries, beam}}) {
    const auto fit = FitComplianceLaw(form, PointsOf(form, c), false);
    for (int i = 0; i < 4; ++i) EXPECT_NEAR(fit.law.cubic.coefficients[i], c[i], 1e-6 * (1 + std::abs(c[i])));
    EXPECT_LT(fit.weighted_chi_square, 1e-12);
  }
}

TEST(ComplianceLawFit, BeamTermsStayNonNegative) {
  // The paper's law implies a slightly negative shaft flexibility; the fit
  // holds it at 0 (a compliance in series cannot be negative).
  const auto fit = FitComplianceLaw(ComplianceForm::kBeamSeries,
                                    PointsOf(ComplianceForm::kInverseCubic, {639.16, -432.35, 136.32, 3.12}), true);
  for (int i = 0; i < 3; ++i) EXPECT_GE(fit.law.cubic.coefficients[i], 0.0);
  EXPECT_EQ(fit.law.cubic.coefficients[3], 0.025);
}

TEST(ComplianceLawFit, CovarianceOfAnExactFitPropagatesThePointSd) {
  // A constant law 1/K = c0 through n points of sd s: var(c0) = s²/n.
  std::vector<DepthCompliance> points;
  for (int i = 0; i < 4; ++i) points.push_back({0.1 + 0.03 * i, 20.0, 0.5});
  const auto fit = FitComplianceLaw(ComplianceForm::kInverseCubic, points, true);
  EXPECT_NEAR(fit.law.cubic.coefficients[3], 20.0, 1e-9);
  // Four coefficients through four points: the fit interpolates; var(1/K) at a
  // point equals that point's variance.
  const Eigen::Vector4d x(0.1 * 0.1 * 0.1, 0.1 * 0.1, 0.1, 1.0);
  EXPECT_NEAR(x.dot(fit.covariance * x), 0.25, 1e-6);
}

TEST(CompareComplianceLaws, PrefersTheLawThatMadeTheData) {
  // At 0.1 % per point (the simulator's per-depth precision) the beam law's
  // 1 % misfit of the paper's curve shows.
  const auto comparison = CompareComplianceLaws(
      PointsOf(ComplianceForm::kInverseCubic, {639.16, -432.35, 136.32, 3.12}, 0.001));
  ASSERT_EQ(comparison.size(), 3u);
  EXPECT_EQ(comparison[0].form, ComplianceForm::kInverseCubic);
  EXPECT_LT(comparison[0].aic, comparison[1].aic);
  EXPECT_LT(comparison[0].aic, comparison[2].aic);
  EXPECT_LT(comparison[0].held_out_rms, 1e-8);
}

// docs/errors.md: a law needs at least as many depths as it has coefficients.
TEST(ComplianceLawFit, TooFewDepthsIsRefusedWithTheCount) {
  auto points = PointsOf(ComplianceForm::kInverseCubic, {639.16, -432.35, 136.32, 3.12});
  points.resize(2);
  try {
    FitComplianceLaw(ComplianceForm::kInverseCubic, points, false);
    ADD_FAILURE() << "fitted a cubic through 2 depths";
  } catch (const std::invalid_argument& e) {
    EXPECT_STREQ(e.what(), "a inverse_cubic law needs 4 depths or more, found 2");
  }
}

}  // namespace
}  // namespace pliant::estimation
