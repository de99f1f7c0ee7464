// `pliant identify` and `pliant params` end to end, as a user meets them.
#include <filesystem>
#include <fstream>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "clamped_beam_log.h"
#include "paper_parameters.h"
#include "pliant/io/log_writer.h"
#include "pliant/io/parameters_json.h"
#include "run_command.h"

namespace pliant {
namespace {

namespace fs = std::filesystem;
using pliant::testing::FreshDirectory;
using pliant::testing::RunCommand;

const std::string kCli = PLIANT_CLI;

fs::path WriteCalibration(const fs::path& dir, pliant::testing::CalibrationLogSpec spec) {
  spec.truth = models::testing::PaperParameters();
  const fs::path path = dir / "calibration.csv";
  io::WriteLog(path.string(), pliant::testing::MakeCalibrationLog(spec));
  return path;
}

TEST(PliantIdentify, WritesParametersThatParamsReadsBack) {
  const auto dir = FreshDirectory("identify_params");
  pliant::testing::CalibrationLogSpec spec;
  spec.depths_m = {0.09, 0.12, 0.15, 0.18, 0.22};
  const auto log = WriteCalibration(dir, spec);
  const auto out = dir / "params.json";
  const auto run = RunCommand(kCli + " identify '" + log.string() + "' -o '" + out.string() + "'", dir);
  ASSERT_EQ(run.exit_code, 0) << run.err;
  EXPECT_NE(run.out.find("joint smoother, inverse_cubic law"), std::string::npos) << run.out;
  EXPECT_NE(run.out.find("joint1.backlash_rad"), std::string::npos) << run.out;
  EXPECT_NE(run.out.find("fit RMS joint 2"), std::string::npos) << run.out;
  EXPECT_NE(run.out.find("condition number"), std::string::npos) << run.out;
  const auto parameters = io::ReadParameters(out.string());  // what `correct` reads
  ASSERT_TRUE(parameters.covariance.has_value());

  const auto params = RunCommand(kCli + " params '" + out.string() + "' --depth 0.12 --json", dir);
  ASSERT_EQ(params.exit_code, 0) << params.err;
  const auto json = nlohmann::json::parse(params.out);
  for (const char* key : {"depth_m", "K1", "K1_sd", "K2", "K2_sd", "delta1", "delta1_sd", "delta2",
                          "delta2_sd"}) {
    EXPECT_TRUE(json.contains(key)) << key;
  }
  const double k1 = 1.0 / (((639.16 * 0.12 - 432.35) * 0.12 + 136.32) * 0.12 + 3.12);
  EXPECT_NEAR(json["K1"].get<double>(), k1, 0.005 * k1);
  EXPECT_GT(json["K1_sd"].get<double>(), 0.0);
  EXPECT_LT(json["K1_sd"].get<double>(), 0.005 * k1);
  EXPECT_NEAR(json["delta2"].get<double>(), 0.007176, 0.0002);
}

TEST(PliantIdentify, SaysWhatALogWithoutHeldTipCannotIdentify) {
  const auto dir = FreshDirectory("identify_free");
  pliant::testing::CalibrationLogSpec spec;
  spec.clamp = false;
  const auto log = WriteCalibration(dir, spec);
  const auto run = RunCommand(kCli + " identify --method paper '" + log.string() + "' -o '" +
                                  (dir / "p.json").string() + "'", dir);
  EXPECT_EQ(run.exit_code, 0) << run.err;
  EXPECT_NE(run.err.find("warning: no tip_fixed samples: compliance K1(L), K2(L), backlash "
                         "delta1, delta2 and the dead-zone widths cannot be identified"),
            std::string::npos) << run.err;
}

TEST(PliantParams, ACorruptParametersFileIsAnInputError) {
  const auto dir = FreshDirectory("params_corrupt");
  std::ofstream(dir / "bad.json") << "{\"format\": \"pliant-parameters\", \"version\": 1,\n \"joint1\": {";
  const auto run = RunCommand(kCli + " params '" + (dir / "bad.json").string() + "' --depth 0.12", dir);
  EXPECT_EQ(run.exit_code, 2);
  EXPECT_NE(run.err.find("bad.json:2:"), std::string::npos) << run.err;
  EXPECT_NE(run.err.find("not valid JSON"), std::string::npos) << run.err;
}

TEST(PliantParams, ADepthInMillimetresIsRefused) {
  const auto dir = FreshDirectory("params_depth");
  const auto run = RunCommand(kCli + " params " + std::string(PLIANT_SOURCE_DIR) +
                                  "/data/paper.json --depth 120", dir);
  EXPECT_EQ(run.exit_code, 2);
  EXPECT_NE(run.err.find("depth 120"), std::string::npos) << run.err;
}

}  // namespace
}  // namespace pliant
