// Study files and trial streams (study.h): the distributions' quantiles
// against their closed forms, the streams' independence of the split, and
// every bad key reported at its line.
#include <cctype>
#include <cmath>
#include <ostream>
#include <set>
#include <string>

#include <gtest/gtest.h>

#include "pliant/experiments/study.h"
#include "pliant/io/input_error.h"

namespace pliant::experiments {
namespace {

const std::string kStudies = PLIANT_SOURCE_DIR "/experiments/studies/";

std::string StudyText(const std::string& extra) {
  return R"({
  "format": "pliant-study", "version": 1, "description": "test",
  "scenario": ")" PLIANT_SOURCE_DIR R"(/experiments/scenarios/divot.json",
  "trials": 10, "seed": 5)" + extra + "\n}\n";
}

TEST(Distribution, QuantilesMatchTheirClosedForms) {
  using K = Distribution::Kind;
  EXPECT_DOUBLE_EQ((Distribution{K::kUniform, 2.0, 6.0}).Quantile(0.25), 3.0);
  // Normal: mean + z·sd with z(0.975) = 1.959963984540054.
  EXPECT_NEAR((Distribution{K::kNormal, 1.0, 0.5}).Quantile(0.975), 1.0 + 0.5 * 1.959963984540054,
              1e-12);
  // Lognormal: the median is exp(μ); its 97.5 % quantile is median·e^(1.96σ).
  EXPECT_NEAR((Distribution{K::kLogNormal, 1.0, 0.1}).Quantile(0.5), 1.0, 1e-14);
  EXPECT_NEAR((Distribution{K::kLogNormal, 2.0, 0.1}).Quantile(0.975),
              2.0 * std::exp(0.1 * 1.959963984540054), 1e-12);
  Distribution clamped{K::kNormal, 0.0, 1.0};
  clamped.lower = -1.0;
  EXPECT_EQ(clamped.Quantile(1e-6), -1.0);
  EXPECT_EQ((Distribution{K::kConstant, 7.0, 0.0}).Quantile(0.9), 7.0);
  EXPECT_TRUE((Distribution{K::kUniform, -90.0, -10.0}).Varies());
  EXPECT_FALSE((Distribution{K::kUniform, 0.1, 0.1}).Varies());
  EXPECT_FALSE((Distribution{K::kNormal, 1.0, 0.0}).Varies());
}

TEST(TrialStream, DependsOnSeedAndTrialOnlyAndIsUniform) {
  TrialStream a(1, 5), b(1, 5), c(1, 6), d(2, 5);
  const auto first = a.Next();
  EXPECT_EQ(first, b.Next());
  EXPECT_NE(first, c.Next());
  EXPECT_NE(first, d.Next());
  // Mean and variance of 100,000 uniforms: 1/2 and 1/12, within 5 standard errors.
  TrialStream s(9, 0);
  double sum = 0.0, squares = 0.0;
  const int n = 100000;
  for (int i = 0; i < n; ++i) {
    const double u = s.Uniform();
    ASSERT_GT(u, 0.0);
    ASSERT_LT(u, 1.0);
    sum += u;
    squares += (u - 0.5) * (u - 0.5);
  }
  EXPECT_NEAR(sum / n, 0.5, 5.0 * std::sqrt(1.0 / 12.0 / n));
  EXPECT_NEAR(squares / n, 1.0 / 12.0, 5.0 * std::sqrt(1.0 / 180.0 / n));
}

TEST(Study, DivotStudyDrawsWhatItDeclares) {
  const Study study = ReadStudy(kStudies + "divot_study.json");
  EXPECT_EQ(study.trials, 1000);
  EXPECT_FALSE(study.identify);
  EXPECT_EQ(study.scenario.type, ExperimentType::kDivot);
  EXPECT_EQ(study.scenario.divot.hold_s, 0.5);  // its scenario_set applied
  // 2,000 draws: the compliance scale's log has sd 0.1 and median 0 (lognormal
  // [1.0, 0.1]); depths are uniform on [0.10, 0.20] m.
  double sum_log = 0.0, sum_log2 = 0.0, min_depth = 1.0, max_depth = 0.0;
  const int n = 2000;
  for (int k = 0; k < n; ++k) {
    TrialStream stream(study.seed, k);
    const TrialDraw draw = DrawTrial(study, stream);
    const double l = std::log(draw.values[kComplianceScale1]);
    sum_log += l;
    sum_log2 += l * l;
    min_depth = std::min(min_depth, draw.values[kDepthM]);
    max_depth = std::max(max_depth, draw.values[kDepthM]);
  }
  EXPECT_NEAR(sum_log / n, 0.0, 5.0 * 0.1 / std::sqrt(n));
  EXPECT_NEAR(std::sqrt(sum_log2 / n), 0.1, 0.1 * 5.0 / std::sqrt(2.0 * n));
  EXPECT_GE(min_depth, 0.10);
  EXPECT_LE(max_depth, 0.20);
  EXPECT_LT(min_depth, 0.101);
  EXPECT_GT(max_depth, 0.199);
}

// A per-joint key takes one distribution for both joints or a pair, joint 1's
// then joint 2's: the shipped studies draw each clearance around its own
// nominal value (the dVRK file's 0.008478 and 0.007176 rad), normal with
// σ 1.15 mrad, as the filter's prior says.
TEST(Study, EachJointMayDrawFromItsOwnDistribution) {
  const Study study = ParseStudy(
      StudyText(R"(, "instrument": {"backlash_rad": [{"uniform": [0.0065, 0.0105]}, 0.007]})"),
      "a.json");
  EXPECT_EQ(study.quantities[kBacklash1Rad].kind, Distribution::Kind::kUniform);
  EXPECT_EQ(study.quantities[kBacklash1Rad].a, 0.0065);
  EXPECT_EQ(study.quantities[kBacklash1Rad].b, 0.0105);
  EXPECT_EQ(study.quantities[kBacklash2Rad].kind, Distribution::Kind::kConstant);
  EXPECT_EQ(study.quantities[kBacklash2Rad].a, 0.007);
  const Study shipped = ReadStudy(kStudies + "divot_study.json");
  const double nominal[2] = {0.008478, 0.007176}, sd = 0.00115;
  const int n = 2000;
  for (int j = 0; j < 2; ++j) {
    double sum = 0.0, squares = 0.0;
    for (int k = 0; k < n; ++k) {
      TrialStream stream(shipped.seed, k);
      const double e = DrawTrial(shipped, stream).values[kBacklash1Rad + j] - nominal[j];
      sum += e;
      squares += e * e;
    }
    // Within 5 standard errors: of the mean, sd/√n; of the sd, sd/√(2n).
    EXPECT_NEAR(sum / n, 0.0, 5.0 * sd / std::sqrt(n)) << "joint " << j + 1;
    EXPECT_NEAR(std::sqrt(squares / n), sd, 5.0 * sd / std::sqrt(2.0 * n)) << "joint " << j + 1;
  }
}

TEST(Study, TheTrialCountDoesNotChangeTheFingerprint) {
  const Study a = ParseStudy(StudyText(""), "a.json");
  Study b = ParseStudy(StudyText("").replace(StudyText("").find("10,"), 3, "99,"), "a.json");
  EXPECT_EQ(b.trials, 99);
  EXPECT_EQ(a.fingerprint, b.fingerprint);
  const Study c = ParseStudy(StudyText(R"(, "noise": {"effort_sd_nm": 0.02})"), "a.json");
  EXPECT_NE(a.fingerprint, c.fingerprint);
}

// The filter's ε: NaN (the filter's own default) unless the study sets it,
// and then part of the fingerprint: results with another ε are another study.
TEST(Study, SetsTheFiltersDeflectionError) {
  const Study plain = ParseStudy(StudyText(""), "a.json");
  EXPECT_TRUE(std::isnan(plain.deflection_model_error));
  const Study set =
      ParseStudy(StudyText(R"(, "filter": {"deflection_model_error": 0.1})"), "a.json");
  EXPECT_EQ(set.deflection_model_error, 0.1);
  EXPECT_NE(plain.fingerprint, set.fingerprint);
}

// The held load's model and the inertial torque's error: the filter's
// defaults unless the study sets them, and part of the fingerprint.
TEST(Study, SetsTheHeldLoadModelAndTheInertialError) {
  const Study plain = ParseStudy(StudyText(""), "a.json");
  EXPECT_TRUE(plain.load_follows_motor);
  EXPECT_TRUE(std::isnan(plain.inertial_torque_error));
  const Study set = ParseStudy(
      StudyText(R"(, "filter": {"load_follows_motor": false, "inertial_torque_error": 0})"), "a.json");
  EXPECT_FALSE(set.load_follows_motor);
  EXPECT_EQ(set.inertial_torque_error, 0.0);
  EXPECT_NE(plain.fingerprint, set.fingerprint);
  EXPECT_EQ(plain.unloaded_start_s, 0.0);
  const Study tared = ParseStudy(StudyText(R"(, "filter": {"unloaded_start_s": 0.15})"), "a.json");
  EXPECT_EQ(tared.unloaded_start_s, 0.15);
  EXPECT_NE(plain.fingerprint, tared.fingerprint);
  EXPECT_TRUE(std::isnan(plain.internal_coulomb_sd_nm));
  const Study arm = ParseStudy(
      StudyText(R"(, "filter": {"internal_inertia_sd_kg_m2": 0.03, "internal_coulomb_sd_nm": 0.02, "internal_viscous_sd_nm_s": 0.01})"),
      "a.json");
  EXPECT_EQ(arm.internal_inertia_sd_kg_m2, 0.03);
  EXPECT_EQ(arm.internal_coulomb_sd_nm, 0.02);
  EXPECT_EQ(arm.internal_viscous_sd_nm_s, 0.01);
  EXPECT_NE(plain.fingerprint, arm.fingerprint);
  EXPECT_TRUE(plain.tip_fixed_hint);
  const Study online = ParseStudy(StudyText(R"(, "filter": {"tip_fixed_hint": false})"), "a.json");
  EXPECT_FALSE(online.tip_fixed_hint);
  EXPECT_NE(plain.fingerprint, online.fingerprint);
}

// Each bad study names its file, line and key.
struct BadStudy {
  std::string extra;
  std::size_t line;
  std::string says;
};

void PrintTo(const BadStudy& bad, std::ostream* os) { *os << "naming " << bad.says; }

class BadStudies : public ::testing::TestWithParam<BadStudy> {};

TEST_P(BadStudies, AreReportedAtTheirLineNamingTheKey) {
  try {
    ParseStudy(StudyText(GetParam().extra), "bad.json");
    FAIL() << "accepted " << GetParam().extra;
  } catch (const io::InputError& e) {
    EXPECT_EQ(e.file(), "bad.json");
    EXPECT_EQ(e.line(), GetParam().line) << e.what();
    EXPECT_NE(std::string(e.what()).find(GetParam().says), std::string::npos) << e.what();
  }
}

INSTANTIATE_TEST_SUITE_P(
    Keys, BadStudies,
    ::testing::Values(
        BadStudy{",\n \"trails\": 3", 5, "trails"},
        BadStudy{",\n \"contact\": {\"depth_m\": {\"uniform\": [0.05, 0.2]}}", 5, "contact.depth_m.uniform"},
        BadStudy{",\n \"instrument\": {\"compliance_scale\": {\"gamma\": [1, 2]}}", 5,
                 "instrument.compliance_scale"},
        BadStudy{",\n \"noise\": {\"effort_sd_nm\": \"loud\"}", 5, "noise.effort_sd_nm"},
        BadStudy{",\n \"identify\": true", 5, "calibration"},
        BadStudy{",\n \"scenario_set\": [\"experiment.hold_s=-1\"]", 5, "scenario_set"},
        BadStudy{",\n \"filter\": {\"deflection_model_error\": -0.1}", 5,
                 "filter.deflection_model_error"},
        BadStudy{",\n \"filter\": {\"gate\": 0.9}", 5, "gate"},
        BadStudy{",\n \"filter\": {\"load_follows_motor\": 1}", 5, "load_follows_motor"},
        BadStudy{",\n \"instrument\": {\"shaft_start\": 1.5}", 5, "instrument.shaft_start"},
        BadStudy{",\n \"instrument\": {\"backlash_rad\": [0.007]}", 5, "two distributions"},
        BadStudy{",\n \"instrument\": {\"backlash_rad\": [0.007, {\"uniform\": [0.01, 0.005]}]}", 5,
                 "instrument.backlash_rad.1.uniform"},
        BadStudy{",\n \"noise\": {\"effort_sd_nm\": [0.01, 0.02]}", 5, "noise.effort_sd_nm"},
        BadStudy{",\n \"filter\": {\"inertial_torque_error\": -0.3}", 5,
                 "filter.inertial_torque_error"},
        BadStudy{",\n \"filter\": {\"unloaded_start_s\": -1}", 5, "filter.unloaded_start_s"},
        BadStudy{",\n \"filter\": {\"internal_coulomb_sd_nm\": -0.1}", 5,
                 "filter.internal_coulomb_sd_nm"},
        BadStudy{",\n \"filter\": {\"tip_fixed_hint\": \"no\"}", 5, "tip_fixed_hint"}),
    [](const ::testing::TestParamInfo<BadStudy>& info) {
      std::string name;  // the key the message must name, as a test name
      for (char c : info.param.says) name += std::isalnum(static_cast<unsigned char>(c)) ? c : '_';
      return name + "_" + std::to_string(info.index);
    });

}  // namespace
}  // namespace pliant::experiments
