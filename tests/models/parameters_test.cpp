#include "pliant/models/parameters.h"

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

}  // namespace
}  // namespace pliant::models
