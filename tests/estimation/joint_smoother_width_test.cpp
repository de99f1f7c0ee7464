// The joint smoother's take-up width, profiled (estimation/src/joint_smoother_width.h,
// docs/decisions/0010-identification-profiled-take-up-width.md): on a clearance
// taken up smoothly the width and the K, δ it biases cover the truth; on a hard
// wall the width ends at its floor and every solve converges.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <string>

#include <gtest/gtest.h>

#include "clamped_beam_log.h"
#include "named_sd.h"
#include "paper_parameters.h"
#include "pliant/estimation/joint_smoother.h"
#include "pliant/estimation/parameter_query.h"

namespace pliant::estimation {
namespace {

IdentificationData CalibrationData(double take_up_nm) {
  testing::CalibrationLogSpec spec;
  spec.truth = models::testing::PaperParameters();
  spec.depths_m = {0.09, 0.12, 0.155, 0.19, 0.22};
  spec.take_up_nm = take_up_nm;
  IdentificationData data;
  AppendSamples(testing::MakeCalibrationLog(spec), "calibration.csv", {}, &data);
  return data;
}

// Every Ceres solve of the report ended in CONVERGENCE, in fewer iterations
// than the cap.
void ExpectEverySolveConverged(const std::string& report, int max_iterations) {
  EXPECT_EQ(report.find("NO_CONVERGENCE"), std::string::npos) << report;
  EXPECT_NE(report.find(" 0 short of convergence"), std::string::npos) << report;
  for (std::size_t at = report.find("Iterations: "); at != std::string::npos;
       at = report.find("Iterations: ", at + 1)) {
    EXPECT_LT(std::stoi(report.substr(at + 12)), max_iterations) << report;
  }
}

// The clearance of both joints taken up over w = 0.15 N·m (pliant's own dead
// zone shape): held at its floor (≈ 0.01 N·m) w makes the shaft reach the wall
// at once, and δ comes out short by tens of its σ; profiled, w, K and δ cover
// the truth.
TEST(JointSmootherWidth, TheProfiledTakeUpCoversTheTruthOnASmoothClearance) {
  const double take_up = 0.15;
  const auto truth = models::testing::PaperParameters();
  const IdentificationData data = CalibrationData(take_up);
  const auto r = RunJointSmoother(data, PaperPrior());
  std::printf("%s", r.report.c_str());
  ExpectEverySolveConverged(r.report, 100);
  ASSERT_TRUE(r.parameters.covariance.has_value());
  for (int j = 0; j < 2; ++j) {
    const std::string joint = "joint" + std::to_string(j + 1);
    const double w = r.parameters.joints[j].deadzone_width_nm;
    const double w_sd = testing::NamedSd(r.parameters, joint + ".deadzone_width_nm");
    std::printf("%s: w %.4f ± %.4f N·m (truth %.2f)\n", joint.c_str(), w, w_sd, take_up);
    EXPECT_LT(std::abs(w - take_up), 3.0 * w_sd);
    EXPECT_LT(w_sd, 0.2 * take_up);  // the logs determine it, not the prior
    for (double depth : {0.09, 0.155, 0.22}) {
      const auto at = QueryParametersAtDepth(r.parameters, depth).joints[j];
      const double k = models::ComplianceAt(truth.joints[j], depth);
      const double delta = truth.joints[j].backlash_rad;
      std::printf("  L %.3f: K %.5f ± %.5f (truth %.5f), δ %.6f ± %.6f (truth %.6f)\n", depth,
                  at.compliance_rad_per_nm, at.compliance_sd, k, at.backlash_rad, at.backlash_sd,
                  delta);
      EXPECT_LT(std::abs(at.compliance_rad_per_nm - k), 3.0 * at.compliance_sd);
      EXPECT_LT(std::abs(at.backlash_rad - delta), 3.0 * at.backlash_sd);
    }
  }
  // The same logs with w held at its floor: δ far outside its σ.
  JointSmootherOptions held;
  held.estimate_deadzone_width = false;
  const auto h = RunJointSmoother(data, PaperPrior(), held);
  for (int j = 0; j < 2; ++j) {
    const auto at = QueryParametersAtDepth(h.parameters, 0.155).joints[j];
    std::printf("w held: δ%d %.6f ± %.6f\n", j + 1, at.backlash_rad, at.backlash_sd);
    EXPECT_GT(std::abs(at.backlash_rad - truth.joints[j].backlash_rad), 5.0 * at.backlash_sd);
  }
}

// A hard wall (the shaft free inside ±δ, on the wall beyond): the profile
// rises from the floor, so w ends there after one solve, and no solve crawls.
// Estimated by Levenberg–Marquardt with w free, this fit ran to the iteration
// cap without converging.
TEST(JointSmootherWidth, AHardWallEndsAtTheFloorAndConverges) {
  const auto truth = models::testing::PaperParameters();
  const auto r = RunJointSmoother(CalibrationData(0.0), PaperPrior());
  std::printf("%s", r.report.c_str());
  ExpectEverySolveConverged(r.report, 60);
  EXPECT_NE(r.report.find("w1 = "), std::string::npos);
  for (int j = 0; j < 2; ++j) {
    // The floor: 4 effort-noise σ of a sample, the log's 0.0025 N·m per row.
    EXPECT_LT(r.parameters.joints[j].deadzone_width_nm, 4.0 * 0.0025 * 1.5);
    const auto at = QueryParametersAtDepth(r.parameters, 0.155).joints[j];
    EXPECT_LT(std::abs(at.backlash_rad - truth.joints[j].backlash_rad), 3.0 * at.backlash_sd);
  }
  std::size_t floors = 0;
  for (std::size_t at = r.report.find("(at its floor)"); at != std::string::npos;
       at = r.report.find("(at its floor)", at + 1))
    ++floors;
  EXPECT_EQ(floors, 2u);
  // At the floor the take-up is below the resolution: a finding, not a warning.
  for (const auto& w : r.warnings) EXPECT_EQ(w.find("dead-zone width"), std::string::npos) << w;
}

}  // namespace
}  // namespace pliant::estimation
