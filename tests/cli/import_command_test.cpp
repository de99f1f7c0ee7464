// pliant import as a user meets it: the format it chose on stderr, the log it
// wrote, and for bad input exit 2, one FILE:LINE: problem — fix line, no output.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include "run_command.h"

namespace pliant {
namespace {

namespace fs = std::filesystem;
using testing::FreshDirectory;
using testing::ReadText;
using testing::RunCommand;

const std::string kCli = PLIANT_CLI;
const std::string kReal = PLIANT_SOURCE_DIR "/data/real/";
const std::string kClamped1 = kReal + "jhu-2017/hysteresis_output_joint_0_2017-7-25-20-30-58.csv";
const std::string kBag = kReal + "crtk-rosbag/pitch_exp_traj_01_test_cropped.bag";

testing::CommandResult Import(const std::string& args, const fs::path& dir) {
  return RunCommand(kCli + " import " + args + " -o '" + (dir / "out.csv").string() + "'", dir);
}

TEST(ImportCommand, SaysTheFormatAndWritesTheLog) {
  const fs::path dir = FreshDirectory("import_good");
  const auto result = Import("'" + kClamped1 + "'", dir);
  ASSERT_EQ(result.exit_code, 0) << result.err;
  EXPECT_EQ(result.err, "pliant import: " + kClamped1 +
                            ": format jhu2017-clamped-beam (from its header row: pos index, depth "
                            "index, depth, current joint position, current joint effort, current "
                            "torque offset)\n");
  EXPECT_EQ(result.out.rfind("pliant import: 1906 rows -> ", 0), 0u) << result.out;
  const std::string log = ReadText(dir / "out.csv");
  EXPECT_NE(log.find("\nt,q1,q3,tau1,tip_fixed,segment,tau1_bias,pose_index\n0,-0.002212563,"),
            std::string::npos);
}

TEST(ImportCommand, ReadsTheBagByArm) {
#ifndef PLIANT_HAVE_ROS1
  GTEST_SKIP() << "pliant was built without ROS 1 (ros/CMakeLists.txt says why)";
#endif
  const fs::path dir = FreshDirectory("import_bag");
  const auto result = Import("--arm PSM2 '" + kBag + "'", dir);
  ASSERT_EQ(result.exit_code, 0) << result.err;
  EXPECT_EQ(result.out.rfind("pliant import: 3420 rows -> ", 0), 0u) << result.out;
  // The shipped log the free-motion tests read is this import, byte for byte.
  EXPECT_EQ(ReadText(dir / "out.csv"), ReadText(kReal + "crtk2022_psm2_free.csv"));
}

struct BadImport {
  std::string name;
  std::string args;          ///< with FILE for the input's path
  std::string input_text;    ///< written to the input file when not empty
  std::string input_name;    ///< the input file's name in the test directory
  std::string message_tail;  ///< what stderr says after "FILE"
};

class ImportError : public ::testing::TestWithParam<BadImport> {};

TEST_P(ImportError, ExitsTwoWithTheMessageAndWritesNothing) {
  const BadImport& c = GetParam();
#ifndef PLIANT_HAVE_ROS1
  if (c.name.find("bag") != std::string::npos || c.name.find("arm") != std::string::npos) {
    GTEST_SKIP() << "pliant was built without ROS 1 (ros/CMakeLists.txt says why)";
  }
#endif
  const fs::path dir = FreshDirectory("import_" + c.name);
  std::string input = dir / c.input_name;
  if (c.input_name == "cut.bag") {
    const std::string bag = ReadText(kBag);
    std::ofstream(input, std::ios::binary) << bag.substr(0, bag.size() / 3);
  } else if (!c.input_text.empty()) {
    std::ofstream(input, std::ios::binary) << c.input_text;
  } else {
    input = c.input_name;
  }
  std::string args = c.args;
  args.replace(args.find("FILE"), 4, "'" + input + "'");
  const auto result = Import(args, dir);
  EXPECT_EQ(result.exit_code, 2) << result.err;
  const std::string last_line = result.err.substr(result.err.rfind(input));
  EXPECT_EQ(last_line.substr(0, input.size() + c.message_tail.size()), input + c.message_tail)
      << result.err;
  EXPECT_FALSE(fs::exists(dir / "out.csv"));
}

const std::string kClampedHeader =
    "pos index,depth index,depth,current joint position,current joint effort,current torque "
    "offset\n";

INSTANTIATE_TEST_SUITE_P(
    Bad, ImportError,
    ::testing::Values(
        BadImport{"truncated_bag", "FILE", "", "cut.bag", ": not a readable ROS 1 bag (rosbag: "},
        BadImport{"wrong_arm", "--arm PSM1 FILE", "", kBag,
                  ": the bag has no /PSM1/measured_js; arms found: PSM2 — pass one of them with "
                  "--arm NAME"},
        BadImport{"other_format", "--format jhu2017-bias-sweep FILE", "", kClamped1,
                  ":1: missing column 'current depth' of the jhu2017-bias-sweep format"},
        BadImport{"missing_column", "FILE",
                  "pos index,depth index,depth,current joint position,current joint effort\n"
                  "0,0,0.1,0.01,0.2\n",
                  "hysteresis_output_joint_0_a.csv",
                  ":1: missing column 'current torque offset' of the jhu2017-clamped-beam format"},
        BadImport{"non_numeric", "FILE",
                  kClampedHeader + "0,0,0.1,0.01,0.2,0.1\n1,0,x,0.01,0.2,0.1\n",
                  "hysteresis_output_joint_1_b.csv",
                  ":3:3: value 'x' in column 'depth' is not a finite number"},
        BadImport{"unknown", "FILE", "a,b\n1,2\n", "other.csv",
                  ":1: the header row (a, b) matches none of the import formats"}),
    [](const auto& info) { return info.param.name; });

// --arm is refused for a CSV: the message names the option, not the file.
TEST(ImportCommand, OptionOfAnotherFormatIsRefused) {
  const fs::path dir = FreshDirectory("import_arm_csv");
  const auto result = Import("--arm PSM1 '" + kClamped1 + "'", dir);
  EXPECT_EQ(result.exit_code, 2);
  EXPECT_NE(result.err.find("--arm: --arm applies to ros1-bag, not jhu2017-clamped-beam — leave "
                            "out --arm\n"),
            std::string::npos)
      << result.err;
  EXPECT_FALSE(fs::exists(dir / "out.csv"));
}

}  // namespace
}  // namespace pliant
