// Parameters an identification bent to absorb an effect. --add on a K(L)
// bent in depth: the added effect is fitted with the compliance's depth tilt,
// which undoes the bend (one scale per joint cannot), and the error falls to
// what the truth's own law leaves. A dead zone widened beyond every push of
// the log: the joint is not compared, and the diagnosis says so.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>

#include "diagnosis_support.h"
#include "pliant/estimation/diagnosis.h"

namespace pliant::testing {
namespace {

// A joint's inverse-cubic K(L) tilted in depth: 1/K' = 1/K − u·x/K_mid, with
// x = (L − L_mid)/half over the joint's depth range and K_mid = K(L_mid):
// K'/K grows by about u from the middle to the deep end.
models::JointParameters Tilted(models::JointParameters joint, double u) {
  const double middle = 0.5 * (joint.depth_min_m + joint.depth_max_m);
  const double half = 0.5 * (joint.depth_max_m - joint.depth_min_m);
  const double k_middle = models::ComplianceAt(joint, middle);
  auto& c = joint.compliance.cubic.coefficients;  // c3, c2, c1, c0 of 1/K
  c[2] -= u / (k_middle * half);
  c[3] += u * middle / (k_middle * half);
  return joint;
}

TEST(DiagnoseAdd, TheAddedEffectIsFittedWithTheCompliancesDepthTilt) {
  const auto scenario = ShortDivot(R"({"deflection_coupling":{"k12":0.004,"k21":-0.004}})");
  const io::Log log = experiments::Simulate(scenario, 7).log;
  const models::ModelParameters truth = ModelOf(scenario);
  models::ModelParameters bent = truth;
  for (int j = 0; j < 2; ++j) {
    ASSERT_EQ(truth.joints[j].compliance.form, models::ComplianceForm::kInverseCubic);
    bent.joints[j] = Tilted(truth.joints[j], 0.08);
  }
  // The bend is what the diagnosis sees at the log's depths (0.11, 0.19 m): K
  // 5–8 % off in opposite directions.
  for (int j = 0; j < 2; ++j) {
    EXPECT_LT(models::ComplianceAt(bent.joints[j], 0.11), 0.96 * models::ComplianceAt(truth.joints[j], 0.11));
    EXPECT_GT(models::ComplianceAt(bent.joints[j], 0.19), 1.04 * models::ComplianceAt(truth.joints[j], 0.19));
  }
  estimation::DiagnoseOptions options;
  options.added_effects = {"deflection_coupling"};
  const auto with_truth = estimation::Diagnose(log, "divot.csv", truth, options);
  const auto with_bent = estimation::Diagnose(log, "divot.csv", bent, options);
  std::printf("  held-out rms with the truth's law %.4f -> %.4f mm, with the bent law %.4f -> %.4f mm\n",
              with_truth.rms_before_mm, with_truth.rms_after_mm, with_bent.rms_before_mm,
              with_bent.rms_after_mm);
  ASSERT_TRUE(with_bent.recalibration.has_value());
  const auto& r = *with_bent.recalibration;
  ASSERT_EQ(r.parameters.size(), 6u);  // s1, s2, d1, d2, u1, u2
  ASSERT_EQ(with_bent.added.size(), 1u);
  const auto& k = with_bent.added[0].parameters;
  std::printf("  tilt u1 = %.4f ± %.2g, u2 = %.4f ± %.2g (bend +0.08); k12 = %.5f, k21 = %.5f\n",
              r.parameters[4], r.parameter_sd[4], r.parameters[5], r.parameter_sd[5], k[0], k[1]);
  // The fitted tilt undoes the bend: u' = −u exactly for this law, within
  // 0.01 (1/8 of it) for the simulator's own physics.
  EXPECT_NEAR(r.parameters[4], -0.08, 0.01);
  EXPECT_NEAR(r.parameters[5], -0.08, 0.01);
  // The coupling as with the truth's law (within 25 % of the truth, as in
  // the catalogue test), and the held-out error within 5 % of the truth's.
  EXPECT_NEAR(k[0], 0.004, 0.001);
  EXPECT_NEAR(k[1], -0.004, 0.001);
  EXPECT_LT(with_bent.rms_after_mm, 1.05 * with_truth.rms_after_mm);
  EXPECT_GT(with_bent.rms_before_mm, 1.2 * with_truth.rms_before_mm);
  // The candidates extend the model with the tilt as fitted: their baseline
  // is no worse than the added effect's own error (without the tilt in it,
  // the bend would come back: 0.43 mm).
  std::printf("  candidates scored against %.4f mm\n", with_bent.rms_recalibrated_mm);
  EXPECT_LT(with_bent.rms_recalibrated_mm, 1.05 * with_bent.rms_after_mm);
}

TEST(DiagnoseInput, AJointNoPushLoadsBeyondItsClearanceLoadIsSaidNotDiagnosed) {
  const auto scenario = ShortDivot("{}");  // pushes of 1 N·m
  const io::Log log = experiments::Simulate(scenario, 3).log;
  models::ModelParameters wide = ModelOf(scenario);
  wide.joints[0].deadzone_width_nm = 0.8;  // compared beyond 2 × 0.8 = 1.6 N·m
  const auto d = estimation::Diagnose(log, "divot.csv", wide, {});
  EXPECT_EQ(d.before.rms_rad[0], 0.0);  // no joint 1 row compared
  EXPECT_GT(d.before.rms_rad[1], 0.0);
  int said = 0;
  for (const auto& note : d.notes) {
    std::printf("  note: %s\n", note.c_str());
    // A width of 0.8 N·m is one the take-up probe looks into: the note says so.
    if (note.find("joint 1 is not diagnosed at the parameters' take-up: no row loads it beyond "
                  "1.6 N·m") != std::string::npos &&
        note.find("dead-zone width 0.8 N·m") != std::string::npos &&
        note.find("the take-up probe compares it") != std::string::npos)
      ++said;
    EXPECT_EQ(note.find("joint 2 is not diagnosed"), std::string::npos) << note;
  }
  EXPECT_EQ(said, 1);
}

}  // namespace
}  // namespace pliant::testing
