// `pliant identify` and `pliant params` end to end, as a user meets them.
#include <cmath>
#include <filesystem>
#include <fstream>
#include <string>

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

TEST(PliantIdentify, WritesParametersThatParamsReadsBack) {
  const auto dir = FreshDirectory("identify_params");
  pliant::testing::CalibrationLogSpec spec;
  spec.depths_m = {0.09, 0.12, 0.15, 0.18, 0.22};
  const auto log = pliant::testing::WritePaperCalibrationLog(dir, spec);
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
  const auto log = pliant::testing::WritePaperCalibrationLog(dir, spec);
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

// `pliant identify` on logs that leave a parameter at its prior: the simulated
// logs data/ ships (truth: experiments/scenarios/*.json, the paper's K and the
// dVRK file's delta, which are also the prior) and a family unlike them (K
// × 0.8, a smaller clearance, another bias). The truth must lie within 3 of
// the stated sd; with a bias sweep and a clamped beam the sd stay small.
const std::string kData = std::string(PLIANT_SOURCE_DIR) + "/data/";

struct Truth {
  double k_scale = 1.0;  ///< K = k_scale / (the paper's inverse cubic)
  double delta1 = 0.008478, delta2 = 0.007176;
  double K(int joint, double depth) const {
    const double c[2][4] = {{639.16, -432.35, 136.32, 3.12}, {3163.17, -1969.15, 448.92, -6.00}};
    const double* a = c[joint - 1];
    return k_scale / (((a[0] * depth + a[1]) * depth + a[2]) * depth + a[3]);
  }
};

struct Error {
  double worst_z = 0.0;         ///< |estimate − truth| / sd, worst of K1, K2, delta1, delta2
  double worst_relative = 0.0;  ///< of K1, K2
  double largest_relative_sd = 0.0;  ///< of K1, K2
};

Error Compare(const fs::path& params, const Truth& truth, const fs::path& dir) {
  Error e;
  for (double depth : {0.10, 0.15, 0.20}) {
    const auto run = RunCommand(kCli + " params '" + params.string() + "' --depth " +
                                    std::to_string(depth) + " --json", dir);
    EXPECT_EQ(run.exit_code, 0) << run.err;
    const auto json = nlohmann::json::parse(run.out);
    for (int j = 1; j <= 2; ++j) {
      const std::string k = "K" + std::to_string(j), d = "delta" + std::to_string(j);
      const double k_true = truth.K(j, depth), k_est = json[k].get<double>();
      const double k_sd = json[k + "_sd"].get<double>();
      const double d_true = j == 1 ? truth.delta1 : truth.delta2;
      e.worst_z = std::max({e.worst_z, std::abs(k_est - k_true) / k_sd,
                            std::abs(json[d].get<double>() - d_true) / json[d + "_sd"].get<double>()});
      e.worst_relative = std::max(e.worst_relative, std::abs(k_est / k_true - 1.0));
      e.largest_relative_sd = std::max(e.largest_relative_sd, k_sd / k_true);
    }
  }
  return e;
}

fs::path Identify(const std::string& logs, const fs::path& dir, const std::string& name,
                  std::string* err = nullptr) {
  const fs::path out = dir / (name + ".json");
  const auto run = RunCommand(kCli + " identify " + logs + " -o '" + out.string() + "'", dir);
  EXPECT_EQ(run.exit_code, 0) << run.err;
  if (err) *err = run.err;
  return out;
}

TEST(IdentifyHeld, ClampedBeamWithoutBiasSweepStatesTheBiasUncertainty) {
  const auto dir = FreshDirectory("identify_held_beam");
  std::string err;
  const auto params = Identify(kData + "clamped_beam.csv", dir, "beam", &err);
  const Error e = Compare(params, Truth{}, dir);
  EXPECT_LT(e.worst_z, 3.0);  // 63 σ (K1) and 315 σ (K2) before the bias was held
  EXPECT_NE(err.find("record a bias sweep"), std::string::npos) << err;
  EXPECT_NE(err.find("the rest is the prior uncertainty of the bias torque tau0 (no bias sweep)"),
            std::string::npos) << err;
}

TEST(IdentifyHeld, DivotPushesLeaveDeltaAtItsPriorWithItsSd) {
  const auto dir = FreshDirectory("identify_held_divot");
  std::string err;
  const auto params =
      Identify(kData + "bias_sweep.csv " + kData + "divot.csv", dir, "divot", &err);
  const Error e = Compare(params, Truth{}, dir);
  EXPECT_LT(e.worst_z, 3.0);  // delta1 9 σ off and K1 9 σ off before delta was held
  EXPECT_NE(err.find("the rest is the prior uncertainty of delta1 (no reversal)"),
            std::string::npos) << err;
}

TEST(IdentifyHeld, AnotherInstrumentFamily) {
  // K × 0.8 (1/K × 1.25), a clearance of 5.5 / 4.5 mrad and a bias unlike the
  // prior's (levels, slopes at the clamp and depth slopes).
  const auto dir = FreshDirectory("identify_held_family");
  const std::string set =
      " --seed 3 --set truth.compliance.joint1=[798.95,-540.4375,170.4,3.9]"
      " --set truth.compliance.joint2=[3953.9625,-2461.4375,561.15,-7.5]"
      " --set truth.backlash_rad=[0.0055,0.0045]"
      " --set 'truth.bias_torque={\"joint1\":{\"angle_rad\":[-1.588,0,1.588],"
      "\"torque_nm\":[0.05,0.12,0.30]},\"joint2\":{\"angle_rad\":[-0.925,0,0.925],"
      "\"torque_nm\":[-0.15,0.02,0.1]},\"depth_slope_nm_per_m\":[0.1,-0.5]}'";
  const std::string scenarios = std::string(PLIANT_SOURCE_DIR) + "/experiments/scenarios/";
  for (const std::string name : {"bias_sweep", "clamped_beam", "divot"}) {
    const auto run = RunCommand(kCli + " simulate " + scenarios + name + ".json -o '" +
                                    (dir / (name + ".csv")).string() + "'" + set +
                                    (name == "divot" ? " --set log.every_n_periods=30" : ""),
                                dir);
    ASSERT_EQ(run.exit_code, 0) << run.err;
  }
  const Truth truth{0.8, 0.0055, 0.0045};
  const std::string sweep = "'" + (dir / "bias_sweep.csv").string() + "' ";
  const std::string beam = "'" + (dir / "clamped_beam.csv").string() + "' ";
  const std::string divot = "'" + (dir / "divot.csv").string() + "' ";

  const Error no_sweep = Compare(Identify(beam, dir, "beam"), truth, dir);
  EXPECT_LT(no_sweep.worst_z, 3.0);
  const Error pushes = Compare(Identify(sweep + divot, dir, "divot"), truth, dir);
  EXPECT_LT(pushes.worst_z, 3.0);
  // The normal case: nothing held, K within 0.5 % and its sd below 0.1 %.
  const Error normal = Compare(Identify(sweep + beam, dir, "normal"), truth, dir);
  EXPECT_LT(normal.worst_relative, 0.005);
  EXPECT_LT(normal.largest_relative_sd, 0.001);
  EXPECT_LT(normal.worst_z, 3.0);
}

// The joint smoother's result must not depend on where malloc puts its blocks
// (Ceres orders a group's blocks by address): the same logs under two heap
// layouts give the same file, byte for byte. Before the blocks shared one
// buffer, the files differed from the first σ on.
TEST(PliantIdentify, TheResultDoesNotDependOnTheHeap) {
  const auto dir = FreshDirectory("identify_heap");
  const std::string logs = "'" + std::string(PLIANT_SOURCE_DIR) + "/data/bias_sweep.csv' '" +
                           std::string(PLIANT_SOURCE_DIR) + "/data/clamped_beam.csv'";
  const auto plain = dir / "plain.json", padded = dir / "padded.json";
  ASSERT_EQ(RunCommand(kCli + " identify " + logs + " -o '" + plain.string() + "'", dir).exit_code, 0);
  const auto run = RunCommand("GLIBC_TUNABLES=glibc.malloc.top_pad=1000003:glibc.malloc.mmap_threshold=4096 " +
                                  kCli + " identify " + logs + " -o '" + padded.string() + "'",
                              dir);
  ASSERT_EQ(run.exit_code, 0) << run.err;
  EXPECT_EQ(pliant::testing::ReadText(plain), pliant::testing::ReadText(padded));
}

}  // namespace
}  // namespace pliant
