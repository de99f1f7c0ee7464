#include "pliant/experiments/scenario.h"

#include <fstream>
#include <iterator>

#include <gtest/gtest.h>

#include "pliant/io/input_error.h"

namespace pliant::experiments {
namespace {

std::string ScenarioPath(const std::string& name) {
  return std::string(PLIANT_SOURCE_DIR) + "/experiments/scenarios/" + name + ".json";
}

// A complete minimal scenario; tests break one thing at a time.
const char* kMinimal = R"({
  "format": "pliant-scenario",
  "version": 1,
  "description": "test",
  "experiment": {"type": "clamped_beam", "depths_m": [0.12, 0.18]},
  "truth": {
    "compliance": {"joint1": [639.16, -432.35, 136.32, 3.12],
                   "joint2": [3163.17, -1969.15, 448.92, -6.00]},
    "backlash_rad": [0.008478, 0.007176]
  }
})";

io::InputError ParseError(const std::string& text, const std::vector<std::string>& sets = {}) {
  try {
    ParseScenario(text, "bad.json", sets);
  } catch (const io::InputError& e) {
    return e;
  }
  ADD_FAILURE() << "no InputError";
  return io::InputError("", 0, 0, "", "");
}

std::string Replace(std::string text, const std::string& from, const std::string& to) {
  text.replace(text.find(from), from.size(), to);
  return text;
}

TEST(Scenario, ThePapersExperimentsLoad) {
  const Scenario clamped = ReadScenario(ScenarioPath("clamped_beam"));
  EXPECT_EQ(clamped.type, ExperimentType::kClampedBeam);
  EXPECT_EQ(clamped.name, "clamped_beam");
  ASSERT_EQ(clamped.clamped_beam.depths_m.size(), 14u);
  EXPECT_DOUBLE_EQ(clamped.clamped_beam.depths_m.front(), 0.09);
  EXPECT_DOUBLE_EQ(clamped.clamped_beam.depths_m.back(), 0.22);
  EXPECT_DOUBLE_EQ(clamped.clamped_beam.tip_step_m, 0.25e-3);
  EXPECT_DOUBLE_EQ(clamped.truth.joints[0].backlash_rad, 0.008478);
  EXPECT_DOUBLE_EQ(clamped.truth.joints[1].backlash_rad, 0.007176);
  EXPECT_EQ(ReadScenario(ScenarioPath("bias_sweep")).bias_sweep.step_deg, 5.0);
  EXPECT_EQ(ReadScenario(ScenarioPath("divot")).type, ExperimentType::kDivot);
  EXPECT_EQ(ReadScenario(ScenarioPath("free_motion")).type, ExperimentType::kFreeMotion);
}

TEST(Scenario, OverridesApplyBeforeTheChecks) {
  const Scenario s =
      ParseScenario(kMinimal, "x.json",
                    {"experiment.depths_m=[0.1]", "sensors.effort_noise_sd_nm=0",
                     "log.mode=hold_means", "hidden_effects.effort_drift.rate1=0.001"});
  EXPECT_EQ(s.clamped_beam.depths_m, std::vector<double>{0.1});
  EXPECT_EQ(s.sensors.effort_noise_sd_nm, 0.0);
  EXPECT_EQ(s.log.mode, LogMode::kHoldMeans);
  ASSERT_EQ(s.hidden_effects.size(), 1u);
  EXPECT_EQ(s.hidden_effects[0].parameters.at("rate1"), 0.001);
}

TEST(Scenario, UnknownKeyNamesItsLineAndTheAllowedKeys) {
  const auto e = ParseError(Replace(kMinimal, "\"backlash_rad\"", "\"backlash\""));
  EXPECT_EQ(e.line(), 9u);
  EXPECT_NE(e.problem().find("unknown key 'backlash' in truth; allowed keys: compliance, "
                             "backlash_rad"),
            std::string::npos)
      << e.what();
}

TEST(Scenario, MissingFieldSaysWhichKeyToAdd) {
  const auto e = ParseError(Replace(kMinimal, "\"description\": \"test\",", ""));
  EXPECT_EQ(e.problem(), "the scenario has no key 'description'");
  const auto f = ParseError(Replace(kMinimal, "\"depths_m\": [0.12, 0.18]", "\"joints\": [1]"));
  EXPECT_EQ(f.problem(), "experiment has no key 'depths_m'");
  EXPECT_EQ(f.line(), 5u);
}

TEST(Scenario, NegativeComplianceIsRefused) {
  const auto e = ParseError(Replace(kMinimal, "[639.16, -432.35, 136.32, 3.12]", "[0, 0, 0, -12]"));
  EXPECT_EQ(e.line(), 7u);
  EXPECT_NE(e.problem().find("joint1: the compliance cubic reaches -12"), std::string::npos)
      << e.what();
}

TEST(Scenario, DepthOutsideTheComplianceRangeIsRefusedAtItsElement) {
  const auto e = ParseError(Replace(kMinimal, "[0.12, 0.18]", "[0.12, 0.25]"));
  EXPECT_EQ(e.line(), 5u);
  EXPECT_EQ(e.problem(), "experiment.depths_m.1 = 0.25 is outside [0.0, 0.24] m");
  const auto f = ParseError(Replace(kMinimal, "[0.12, 0.18]", "[0.05]"));
  EXPECT_EQ(f.problem(), "depth 0.05 m is outside the truth's compliance range [0.09, 0.22] m");
}

TEST(Scenario, AShaftThatStartsBeyondItsWallIsRefused) {
  const auto e = ParseError(Replace(kMinimal, "\"backlash_rad\": [0.008478, 0.007176]",
                                    "\"backlash_rad\": [0.008478, 0.007176],\n"
                                    "    \"initial_shaft_offset_rad\": [0.001, -0.0072]"));
  EXPECT_EQ(e.line(), 10u);
  EXPECT_EQ(e.problem(), "joint 2's shaft starts at or beyond its wall") << e.what();
}

TEST(Scenario, OverrideErrorsNameTheOverride) {
  const auto e = ParseError(kMinimal, {"experiment.depths_m=[0.3]"});
  EXPECT_EQ(e.file(), "--set experiment.depths_m=[0.3]");
  EXPECT_EQ(e.line(), 0u);
  const auto f = ParseError(kMinimal, {"no_equals_sign"});
  EXPECT_EQ(f.problem(), "an override must be key=value");
  // A key below an array or a number would index it (found by fuzzing: an
  // index of 10^11 grew an array until memory ran out).
  const auto g = ParseError(kMinimal, {"experiment.depths_m.99999999999=1"});
  EXPECT_EQ(g.file(), "--set experiment.depths_m.99999999999=1");
  EXPECT_EQ(g.problem(),
            "cannot set experiment.depths_m.99999999999: experiment.depths_m is not an object");
}

TEST(Scenario, HiddenEffectsComeFromTheCatalogue) {
  const std::string with =
      Replace(kMinimal, "\"truth\":", "\"hidden_effects\": {\"stiction\": {}},\n  \"truth\":");
  const auto e = ParseError(with);
  EXPECT_NE(e.problem().find("no effect named 'stiction' in the catalogue; known: "),
            std::string::npos);
  const auto f = ParseError(kMinimal, {"hidden_effects.joint_friction.viscous=0.1"});
  EXPECT_NE(f.problem().find("unknown key 'viscous'"), std::string::npos) << f.what();
  const auto g = ParseError(kMinimal, {"hidden_effects.compliance={}"});
  EXPECT_EQ(g.problem(), "'compliance' is part of the truth, not a hidden effect");
}

TEST(Scenario, NotJsonPointsAtTheSyntaxError) {
  const auto e = ParseError("{\n  \"format\": \"pliant-scenario\",,\n}");
  EXPECT_EQ(e.line(), 2u);
  EXPECT_EQ(e.problem().rfind("not valid JSON: syntax error", 0), 0u) << e.problem();
}

// Fuzzing found a number beyond a double escaping as nlohmann's out_of_range;
// the scenario reader now shares io::ParseJsonInput with the parameters reader.
TEST(Scenario, NumberBeyondADoubleAndRepeatedKeysAreInputErrors) {
  const auto big = ParseError("{\n  \"format\": \"pliant-scenario\",\n  \"version\": 1e999\n}");
  EXPECT_EQ(big.line(), 3u);
  EXPECT_EQ(big.problem(), "number 1e999 does not fit in a double");
  const auto twice = ParseError("{\"format\": \"pliant-scenario\",\n \"format\": \"x\"}");
  EXPECT_EQ(twice.line(), 2u);
  EXPECT_EQ(twice.problem(), "duplicate key 'format' in the top-level object");
  std::ifstream found(std::string(PLIANT_SOURCE_DIR) +
                      "/tests/fuzz/regressions/scenario/number_overflow.json");
  const std::string text((std::istreambuf_iterator<char>(found)), std::istreambuf_iterator<char>());
  ASSERT_FALSE(text.empty());
  EXPECT_NE(ParseError(text).problem().find("does not fit in a double"), std::string::npos);
}

}  // namespace
}  // namespace pliant::experiments
