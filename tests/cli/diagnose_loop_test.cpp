// The loop the diagnosis promises ends in corrected joints: diagnose, --add
// the named effect, --write-params, and `pliant correct` and `pliant filter`
// with that file on a log the diagnosis never saw are closer to the truth.
#include <gtest/gtest.h>

#include <cstdio>
#include <filesystem>
#include <string>
#include <vector>

#include "pliant/io/file_checksum.h"
#include "pliant/io/log_reader.h"
#include "pliant/io/parameters_json.h"
#include "loaded_rms_error.h"
#include "run_command.h"

namespace pliant::testing {
namespace {

namespace fs = std::filesystem;
const std::string kCli = PLIANT_CLI;
const std::string kSource = PLIANT_SOURCE_DIR;
const std::string kParams = kSource + "/data/paper.json";
const std::string kHiddenLog = kSource + "/data/divot_hidden_effect.csv";

TEST(DiagnoseLoop, TheWrittenParametersCorrectALogTheDiagnosisNeverSaw) {
  const auto dir = FreshDirectory("diagnose_loop");
  // The shipped log hides deflection_coupling k12 0.006, k21 0.004 (data/README.md).
  const auto d = RunIn(dir, kCli + " diagnose --params " + kParams + " " + kHiddenLog +
                                " --add deflection_coupling --candidate joint_friction"
                                " --write-params with.json -o report");
  ASSERT_EQ(d.exit_code, 0) << d.err;
  EXPECT_NE(d.out.find("wrote with.json"), std::string::npos) << d.out;
  const auto written = io::ReadParameters((dir / "with.json").string());
  ASSERT_EQ(written.effects.size(), 1u);
  EXPECT_EQ(written.effects[0].name, "deflection_coupling");
  ASSERT_EQ(written.effects[0].values.size(), 2u);
  EXPECT_NEAR(written.effects[0].values[0], 0.006, 0.0003);  // k12, rad/(N·m)
  EXPECT_NEAR(written.effects[0].values[1], 0.004, 0.0003);  // k21
  EXPECT_GT(written.effects[0].sd[0], 0.0);
  // The coupling was fitted on the diagnosed log: the file records it.
  ASSERT_EQ(written.identified_from.size(), 1u);
  EXPECT_EQ(written.identified_from[0].file, kHiddenLog);
  EXPECT_EQ(written.identified_from[0].crc32, io::FileCrc32(kHiddenLog));

  // Another log with the same instrument and effect, another seed and depth.
  const auto sim = RunIn(
      dir, kCli + " simulate " + kSource + "/experiments/scenarios/divot.json -o other.csv" +
               " --seed 5 --set log.every_n_periods=30 --set experiment.depths_m=[0.13]" +
               " --set 'hidden_effects={\"deflection_coupling\":{\"k12\":0.006,\"k21\":0.004}}'");
  ASSERT_EQ(sim.exit_code, 0) << sim.err;
  // Measured: correct joint 1 2.65 -> 1.47, joint 2 1.82 -> 0.53 mrad; the
  // filter (the file's deflection effect in its measurement model,
  // filter_deflection.cpp) joint 1 1.39 -> 1.07, joint 2 0.26 -> 0.15 mrad,
  // the tip 0.154 -> 0.124 mm.
  ExpectLoadedErrorFalls(dir, kCli, "correct", kParams, "with.json", 0.7);
  ExpectLoadedErrorFalls(dir, kCli, "filter", kParams, "with.json", 0.85);
}

TEST(DiagnoseLoop, WriteParamsWithoutAnAddedEffectIsBadInput) {
  const auto dir = FreshDirectory("diagnose_loop_no_add");
  const auto r = RunIn(dir, kCli + " diagnose --params " + kParams + " " + kHiddenLog +
                                " --write-params with.json -o report");
  EXPECT_EQ(r.exit_code, 2) << r.err;
  EXPECT_NE(r.err.find("--add"), std::string::npos) << r.err;
  EXPECT_FALSE(fs::exists(dir / "with.json"));
  EXPECT_FALSE(fs::exists(dir / "report"));
}

}  // namespace
}  // namespace pliant::testing
