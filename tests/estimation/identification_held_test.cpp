// The joint smoother when the logs leave a parameter at its prior: held there,
// with the prior's uncertainty carried into the sd of K and delta, so that the
// truth lies within the stated sd (tests/support/clamped_beam_log.h's truth).
#include <cmath>
#include <string>

#include <gtest/gtest.h>

#include "clamped_beam_log.h"
#include "paper_parameters.h"
#include "pliant/estimation/identification.h"
#include "pliant/estimation/joint_smoother.h"
#include "pliant/estimation/parameter_query.h"

namespace pliant::estimation {
namespace {

IdentificationData Data(const testing::CalibrationLogSpec& spec) {
  IdentificationData data;
  AppendSamples(testing::MakeCalibrationLog(spec), "calibration.csv", {}, &data);
  return data;
}

testing::CalibrationLogSpec PaperSweeps() {
  testing::CalibrationLogSpec spec;
  spec.truth = models::testing::PaperParameters();
  for (int i = 0; i < 14; ++i) spec.depths_m.push_back(0.09 + 0.01 * i);
  return spec;
}

// |K − truth| in units of the reported sd, worst over joints and depths.
double WorstComplianceZ(const IdentificationResult& r, const models::ModelParameters& truth) {
  double worst = 0.0;
  for (double depth : {0.09, 0.155, 0.22}) {
    const auto at = QueryParametersAtDepth(r.parameters, depth);
    for (int j = 0; j < 2; ++j) {
      const double k = models::ComplianceAt(truth.joints[j], depth);
      worst = std::max(worst, std::abs(at.joints[j].compliance_rad_per_nm - k) /
                                  at.joints[j].compliance_sd);
    }
  }
  return worst;
}

bool HasWarningStarting(const IdentificationResult& r, const std::string& start) {
  for (const auto& w : r.warnings) if (w.rfind(start, 0) == 0) return true;
  return false;
}

TEST(HeldParameters, WithoutABiasSweepKCarriesTheBiasPriorsUncertainty) {
  testing::CalibrationLogSpec spec = PaperSweeps();
  spec.bias_sweep = false;
  const auto r = RunJointSmoother(Data(spec), PaperPrior());
  EXPECT_LT(WorstComplianceZ(r, spec.truth), 3.0);
  // The bias prior (sd 0.5 N·m per Fourier term) leaves tau0's slope at the
  // clamp, b1 + 2·b2, uncertain by 1.1 N·m/rad, which 1/K ≈ 16 N·m/rad of
  // joint 1 cannot tell from its own: several per cent of K.
  const auto at = QueryParametersAtDepth(r.parameters, 0.155).joints[0];
  EXPECT_GT(at.compliance_sd / at.compliance_rad_per_nm, 0.03);
  for (int j = 0; j < 2; ++j) {
    const double delta = spec.truth.joints[j].backlash_rad;
    EXPECT_LT(std::abs(r.parameters.joints[j].backlash_rad - delta),
              3.0 * QueryParametersAtDepth(r.parameters, 0.155).joints[j].backlash_sd);
  }
  EXPECT_TRUE(HasWarningStarting(r, "no free-tip samples (no bias sweep)"));
  EXPECT_TRUE(HasWarningStarting(r, "joint 1: K1 at 0.155 m"));
}

TEST(HeldParameters, WithoutAReversalDeltaReportsItsPriorAndKCarriesIt) {
  testing::CalibrationLogSpec spec = PaperSweeps();
  spec.reversals = false;
  // A smaller clearance than the prior's 0.008478 / 0.007176 rad.
  spec.truth.joints[0].backlash_rad = 0.005;
  spec.truth.joints[1].backlash_rad = 0.004;
  const auto r = RunJointSmoother(Data(spec), PaperPrior());
  const auto at = QueryParametersAtDepth(r.parameters, 0.155);
  for (int j = 0; j < 2; ++j) {
    EXPECT_DOUBLE_EQ(r.parameters.joints[j].backlash_rad, PaperPrior().joints[j].backlash_rad);
    EXPECT_NEAR(at.joints[j].backlash_sd, 0.004, 1e-12);  // the backlash prior's sd
  }
  EXPECT_LT(WorstComplianceZ(r, spec.truth), 3.0);
  EXPECT_TRUE(HasWarningStarting(r, "joint 2: K2 at 0.155 m"));
}

TEST(HeldParameters, WithABiasSweepAndReversalsNothingIsHeld) {
  const auto r = RunJointSmoother(Data(PaperSweeps()), PaperPrior());
  EXPECT_TRUE(r.warnings.empty()) << r.warnings.front();
  const auto at = QueryParametersAtDepth(r.parameters, 0.155).joints[0];
  EXPECT_LT(at.compliance_sd / at.compliance_rad_per_nm, 0.002);
}

}  // namespace
}  // namespace pliant::estimation
