// `pliant correct` end to end: the process, its exit codes, its messages and
// its output file, as a user meets them.
#include <filesystem>
#include <fstream>

#include <gtest/gtest.h>

#include "pliant/io/log_reader.h"
#include "run_command.h"

namespace pliant {
namespace {

namespace fs = std::filesystem;
using testing::FreshDirectory;
using testing::RunCommand;

const std::string kCli = PLIANT_CLI;
const std::string kParams = std::string(PLIANT_SOURCE_DIR) + "/data/paper.json";

std::string Correct(const fs::path& input, const fs::path& output,
                    const std::string& extra = "") {
  return kCli + " correct --params " + kParams + " " + extra + " '" + input.string() + "' -o '" +
         output.string() + "'";
}

void WriteText(const fs::path& path, const std::string& text) {
  std::ofstream(path, std::ios::binary) << text;
}

TEST(PliantCli, VersionAndHelp) {
  const auto dir = FreshDirectory("cli_version");
  const auto version = RunCommand(kCli + " --version", dir);
  EXPECT_EQ(version.exit_code, 0);
  EXPECT_EQ(version.out, "pliant 0.1.0\n");
  const auto help = RunCommand(kCli + " correct --help", dir);
  EXPECT_EQ(help.exit_code, 0);
  EXPECT_NE(help.out.find("--params"), std::string::npos);
  EXPECT_NE(help.out.find("deadzone"), std::string::npos);
}

TEST(PliantCli, UsageErrorsExitTwo) {
  const auto dir = FreshDirectory("cli_usage");
  EXPECT_EQ(RunCommand(kCli, dir).exit_code, 2);
  EXPECT_EQ(RunCommand(kCli + " correct", dir).exit_code, 2);
  const auto bad_model = RunCommand(kCli + " correct --params x.json --model magic a.csv -o b.csv", dir);
  EXPECT_EQ(bad_model.exit_code, 2);
  EXPECT_NE(bad_model.err.find("magic"), std::string::npos) << bad_model.err;
}

TEST(PliantCli, CorrectsTheShippedSampleAndReportsTheTipError) {
  const auto dir = FreshDirectory("cli_sample");
  const fs::path input = std::string(PLIANT_SOURCE_DIR) + "/data/divot_push.csv";
  const auto result = RunCommand(Correct(input, dir / "out.csv"), dir);
  ASSERT_EQ(result.exit_code, 0) << result.err;
  EXPECT_NE(result.out.find("tip error against q*_true"), std::string::npos) << result.out;
  const io::Log in = io::ReadLog(input.string());
  const io::Log out = io::ReadLog((dir / "out.csv").string());
  EXPECT_EQ(out.Rows(), in.Rows());
  EXPECT_EQ(out.header.columns.size(), in.header.columns.size() + 2);
  EXPECT_EQ(out.header.columns.back(), "q2_corr");
  // Metadata and the auxiliary channel are carried through unchanged.
  EXPECT_EQ(out.header.Metadata("generator"), in.header.Metadata("generator"));
  EXPECT_EQ(out.Column("motor_temperature_c"), in.Column("motor_temperature_c"));
  EXPECT_EQ(out.header.Metadata("correction").rfind("paper model", 0), 0u);
}

// One bad input of each class the log contract names, the line and column the
// message must point at, and words of the fix.
struct BadInput {
  const char* name;
  const char* content;
  const char* where;     // ":LINE:" or ":LINE:COLUMN:" after the file name ("" for none)
  const char* problem;   // words the message must contain
};

void PrintTo(const BadInput& bad, std::ostream* os) { *os << bad.name; }

class BadLog : public ::testing::TestWithParam<BadInput> {};

TEST_P(BadLog, ExitsTwoWithFileLineAndFixAndLeavesNoOutput) {
  const BadInput bad = GetParam();
  const auto dir = FreshDirectory(std::string("cli_bad_") + bad.name);
  const fs::path input = dir / "in.csv";
  if (std::string(bad.name) != "missing_file") WriteText(input, bad.content);
  const auto result = RunCommand(Correct(input, dir / "out.csv"), dir);
  EXPECT_EQ(result.exit_code, 2) << result.err;
  EXPECT_EQ(result.err.rfind(input.string() + bad.where, 0), 0u) << result.err;
  EXPECT_NE(result.err.find(bad.problem), std::string::npos) << result.err;
  EXPECT_NE(result.err.find(" — "), std::string::npos) << "no fix given: " << result.err;
  EXPECT_FALSE(fs::exists(dir / "out.csv"));
  for (const auto& entry : fs::directory_iterator(dir)) {
    EXPECT_EQ(entry.path().filename().string().find(".tmp"), std::string::npos)
        << "temporary file left: " << entry.path();
  }
}

const char kHeader[] = "t,q1,q2,q3,tau1,tau2\n";

INSTANTIATE_TEST_SUITE_P(
    EveryClass, BadLog,
    ::testing::Values(
        BadInput{"missing_file", "", ":", "cannot open"},
        BadInput{"empty_file", "", ":", "empty"},
        BadInput{"missing_column", "t,q1,q2,q3,tau1\n0,0,0,0.1,0\n", ":1:", "tau2"},
        BadInput{"duplicate_column", "t,q1,q2,q3,tau1,tau2,q1\n0,0,0,0.1,0,0,0\n", ":1:7:",
                 "q1"},
        BadInput{"field_count", "t,q1,q2,q3,tau1,tau2\n0,0,0,0.1,0\n", ":2:", "5 fields"},
        BadInput{"not_a_number", "t,q1,q2,q3,tau1,tau2\n0,0,abc,0.1,0,0\n", ":2:3:", "abc"},
        BadInput{"nan_required", "t,q1,q2,q3,tau1,tau2\n0,0,nan,0.1,0,0\n", ":2:3:", "q2"},
        BadInput{"inf_required", "t,q1,q2,q3,tau1,tau2\n0,0,0,0.1,inf,0\n", ":2:5:", "tau1"},
        BadInput{"t_not_increasing", "t,q1,q2,q3,tau1,tau2\n1,0,0,0.1,0,0\n1,0,0,0.1,0,0\n",
                 ":3:1:", "not greater"},
        BadInput{"degrees", "t,q1,q2,q3,tau1,tau2\n0,45,0,0.1,0,0\n", ":2:2:", "degrees"},
        BadInput{"millimetres", "t,q1,q2,q3,tau1,tau2\n0,0,0,120,0,0\n", ":2:4:", "millimetres"},
        BadInput{"effort_units", "t,q1,q2,q3,tau1,tau2\n0,0,0,0.1,0,250\n", ":2:6:", "units"},
        BadInput{"no_rows", "t,q1,q2,q3,tau1,tau2\n", ":", "no data rows"}),
    [](const auto& info) { return std::string(info.param.name); });

TEST(PliantCli, SkipBadRowsDropsAndCountsThem) {
  const auto dir = FreshDirectory("cli_skip");
  WriteText(dir / "in.csv", std::string(kHeader) +
                                "0,0,0,0.1,0,0\n0.01,nan,0,0.1,0,0\n0.02,0,0,0.1,,0\n"
                                "0.03,0,0,0.1,0.5,0\n");
  const auto result = RunCommand(Correct(dir / "in.csv", dir / "out.csv", "--skip-bad-rows"), dir);
  ASSERT_EQ(result.exit_code, 0) << result.err;
  EXPECT_NE(result.out.find("skipped 2 bad rows"), std::string::npos) << result.out;
  EXPECT_EQ(io::ReadLog((dir / "out.csv").string()).Rows(), 2u);
}

TEST(PliantCli, BadParametersExitTwoAndKeepAnOldOutput) {
  const auto dir = FreshDirectory("cli_bad_params");
  WriteText(dir / "in.csv", std::string(kHeader) + "0,0,0,0.1,0,0\n");
  WriteText(dir / "out.csv", "precious\n");
  WriteText(dir / "p.json", "{\"format\": \"pliant-parameters\", \"version\": 1,\n \"jiont1\": {}}\n");
  const auto result = RunCommand(kCli + " correct --params '" + (dir / "p.json").string() + "' '" +
                                     (dir / "in.csv").string() + "' -o '" +
                                     (dir / "out.csv").string() + "'",
                                 dir);
  EXPECT_EQ(result.exit_code, 2);
  EXPECT_EQ(result.err.rfind((dir / "p.json").string() + ":2:", 0), 0u) << result.err;
  EXPECT_NE(result.err.find("jiont1"), std::string::npos) << result.err;
  EXPECT_EQ(testing::ReadText(dir / "out.csv"), "precious\n");
}

TEST(PliantCli, DepthOutsideTheValidRangeWarnsOnceWithACount) {
  const auto dir = FreshDirectory("cli_depth");
  WriteText(dir / "in.csv", std::string(kHeader) +
                                "0,0,0,0.05,1,0\n0.01,0,0,0.06,1,0\n0.02,0,0,0.15,1,0\n");
  const auto result = RunCommand(Correct(dir / "in.csv", dir / "out.csv"), dir);
  ASSERT_EQ(result.exit_code, 0) << result.err;
  EXPECT_NE(result.err.find("warning: 2 rows have an insertion depth outside"), std::string::npos)
      << result.err;
  EXPECT_EQ(result.err.find("warning", 10), std::string::npos) << "warned more than once";
}

}  // namespace
}  // namespace pliant
