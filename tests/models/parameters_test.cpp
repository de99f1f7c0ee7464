#include "pliant/models/parameters.h"

#include <cmath>

#include <gtest/gtest.h>

#include "paper_parameters.h"

namespace pliant::models {
namespace {

// K(L) of the paper's equations (3) and (4) at the ends and middle of the
// calibrated range; the denominators were summed by hand term by term.
struct ComplianceCase {
  int joint;
  double depth_m;
  double inverse_k;
};

class PaperCompliance : public ::testing::TestWithParam<ComplianceCase> {};

TEST_P(PaperCompliance, MatchesHandComputedValue) {
  const auto c = GetParam();
  const ModelParameters p = testing::PaperParameters();
  EXPECT_NEAR(ComplianceAt(p.joints[c.joint], c.depth_m), 1.0 / c.inverse_k, 1e-12);
}

INSTANTIATE_TEST_SUITE_P(
    Equations3And4, PaperCompliance,
    ::testing::Values(ComplianceCase{0, 0.09, 0.46594764 - 3.502035 + 12.2688 + 3.12},
                      ComplianceCase{0, 0.15, 2.157165 - 9.727875 + 20.448 + 3.12},
                      ComplianceCase{0, 0.22, 6.80577568 - 20.92574 + 29.9904 + 3.12},
                      ComplianceCase{1, 0.09, 2.30595093 - 15.950115 + 40.4028 - 6.0},
                      ComplianceCase{1, 0.15, 10.67569875 - 44.305875 + 67.338 - 6.0},
                      ComplianceCase{1, 0.22, 33.68143416 - 95.30686 + 98.7624 - 6.0}));

TEST(Parameters, ComplianceIsClampedToTheValidRange) {
  const ModelParameters p = testing::PaperParameters();
  EXPECT_DOUBLE_EQ(ComplianceAt(p.joints[1], 0.01), ComplianceAt(p.joints[1], 0.09));
  EXPECT_DOUBLE_EQ(ComplianceAt(p.joints[1], 0.30), ComplianceAt(p.joints[1], 0.22));
}

TEST(Parameters, DirectFormIsEvaluatedAsK) {
  ModelParameters p = testing::PaperParameters();
  p.joints[0].compliance = {ComplianceForm::kDirectCubic, {{-38.3402, 22.6, -4.5406, 0.3458}}};
  // dVRK file, joint 1, at 0.15 m: −0.129398175 + 0.5085 − 0.68109 + 0.3458
  EXPECT_NEAR(ComplianceAt(p.joints[0], 0.15), -0.129398175 + 0.5085 - 0.68109 + 0.3458, 1e-12);
  EXPECT_EQ(ValidateParameters(p), "");
}

TEST(Parameters, PaperParametersAreValid) {
  EXPECT_EQ(ValidateParameters(testing::PaperParameters()), "");
}

TEST(Parameters, RejectsARangeWhereInverseKCrossesZero) {
  ModelParameters p = testing::PaperParameters();
  p.joints[1].depth_min_m = 0.01;
  EXPECT_EQ(ValidateParameters(p).rfind("joint2: the compliance cubic reaches ", 0), 0u)
      << ValidateParameters(p);
}

TEST(Parameters, RejectsMalformedTablesAndRanges) {
  ModelParameters p = testing::PaperParameters();
  p.joints[0].bias_torque.angle_rad = {0.0, 0.0};
  EXPECT_EQ(ValidateParameters(p),
            "joint1: bias_torque angle_rad must be strictly increasing (entry 1)");
  p = testing::PaperParameters();
  p.joints[1].depth_max_m = 0.05;
  EXPECT_EQ(ValidateParameters(p),
            "joint2: depth_range_m must be [min, max] with 0 < min < max <= 0.3 m");
  p = testing::PaperParameters();
  p.joints[0].deadzone_width_nm = 0.0;
  EXPECT_EQ(ValidateParameters(p), "joint1: deadzone_width_nm must be in (0, 10) N·m");
}

TEST(Parameters, BeamSeriesAddsJointStructureAndShaftCompliance) {
  ModelParameters p = testing::PaperParameters();
  p.joints[0].compliance = {ComplianceForm::kBeamSeries, {{0.03, 0.004, 0.8, 0.025}}};
  // Beyond the cannula the shaft is a cantilever: F·l³/(3EI) at the tip, seen
  // from the RCM as (F·l³/(3EI))/L with F = tau/L.
  const double L = 0.2, l = 0.2 - 0.025;
  EXPECT_NEAR(ComplianceAt(p.joints[0], L), 0.03 + 0.004 / L + 0.8 * l * l * l / (3 * L * L), 1e-15);
  p.joints[0].depth_min_m = 0.02;  // inside the cannula: no shaft term
  EXPECT_NEAR(ComplianceAt(p.joints[0], 0.02), 0.03 + 0.004 / 0.02, 1e-15);
  EXPECT_EQ(ValidateParameters(p), "");
}

TEST(Parameters, BeamSeriesMustBeNonNegativeAndSomewherePositive) {
  ModelParameters p = testing::PaperParameters();
  p.joints[1].compliance = {ComplianceForm::kBeamSeries, {{0.03, -0.001, 0.8, 0.025}}};
  EXPECT_EQ(ValidateParameters(p).rfind("joint2: compliance beam_series terms must be finite and >= 0", 0), 0u);
  p.joints[1].compliance = {ComplianceForm::kBeamSeries, {{0.0, 0.0, 0.8, 0.095}}};
  EXPECT_EQ(ValidateParameters(p).rfind("joint2: the compliance beam_series law is zero somewhere", 0), 0u);
  p.joints[1].compliance.cubic.coefficients[3] = 0.025;  // the shaft alone, beyond the cannula
  EXPECT_EQ(ValidateParameters(p), "");
}

TEST(Parameters, FourierBiasIsEvaluatedWithItsDepthTerms) {
  JointParameters joint = testing::PaperParameters().joints[1];
  joint.bias_form = BiasForm::kFourier;
  joint.bias_fourier = {{0.03, 0.01, 0.12}, -0.2419, 0.155, {0.3, -0.5}};
  // (L − L_ref)·(s + c1·cos q + d1·sin q) at L − L_ref = 0.045 m.
  EXPECT_NEAR(BiasTorqueAt(joint, 0.3, 0.2),
              0.03 + 0.01 * std::cos(0.3) + 0.12 * std::sin(0.3) +
                  0.045 * (-0.2419 + 0.3 * std::cos(0.3) - 0.5 * std::sin(0.3)),
              1e-15);
  // At the reference depth the depth terms vanish whatever the angle.
  EXPECT_NEAR(BiasTorqueAt(joint, 1.1, 0.155),
              0.03 + 0.01 * std::cos(1.1) + 0.12 * std::sin(1.1), 1e-15);
  ModelParameters p = testing::PaperParameters();
  p.joints[1] = joint;
  EXPECT_EQ(ValidateParameters(p), "");
  p.joints[1].bias_fourier.coefficients = {0.1, 0.2};
  EXPECT_EQ(ValidateParameters(p),
            "joint2: bias_torque coefficients must be a0, a1, b1, … (an odd number, at least one)");
}

// The names the parameters file, identify --model and pliant.identify's law= share.
TEST(Parameters, EachFormIsNamedAndReadBack) {
  for (auto form : {ComplianceForm::kInverseCubic, ComplianceForm::kDirectCubic,
                    ComplianceForm::kBeamSeries}) {
    ComplianceForm read = form == ComplianceForm::kBeamSeries ? ComplianceForm::kInverseCubic
                                                              : ComplianceForm::kBeamSeries;
    ASSERT_TRUE(ComplianceFormNamed(ComplianceFormName(form), &read)) << ComplianceFormName(form);
    EXPECT_EQ(read, form);
  }
  ComplianceForm untouched = ComplianceForm::kDirectCubic;
  EXPECT_FALSE(ComplianceFormNamed("cubic", &untouched));
  EXPECT_EQ(untouched, ComplianceForm::kDirectCubic);
}

}  // namespace
}  // namespace pliant::models
