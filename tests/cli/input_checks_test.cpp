// Issue-29 inputs as a user meets them: each was accepted silently (or with
// the wrong exit status, or library chatter) and is now refused or warned with
// its message.
#include <cmath>
#include <filesystem>
#include <fstream>
#include <string>

#include <gtest/gtest.h>

#include "pliant/io/log_reader.h"
#include "pliant/io/log_writer.h"
#include "run_command.h"

namespace pliant {
namespace {

namespace fs = std::filesystem;
using testing::FreshDirectory;
using testing::ReadText;
using testing::RunCommand;

const std::string kCli = PLIANT_CLI;
const std::string kSource = PLIANT_SOURCE_DIR;
const std::string kParams = kSource + "/data/paper.json";
const std::string kDvrkFile = kSource + "/data/real/jhu-2017/dvrk-compensation.json";

std::string Quoted(const fs::path& path) { return "'" + path.string() + "'"; }

// data/clamped_beam.csv with every angle and angular velocity in degrees
// divided by `shrink` (so that they can stay inside the joints' range in rad).
fs::path ClampedBeamInDegrees(const fs::path& dir, double shrink) {
  io::Log log = io::ReadLog(kSource + "/data/clamped_beam.csv");
  for (const char* name : {"q1", "q2", "q1_cmd", "q2_cmd", "q1_true", "q2_true", "v1", "v2"}) {
    const int column = log.header.Index(name);
    if (column < 0) continue;
    for (std::size_t row = 0; row < log.Rows(); ++row) {
      log.values[row * log.Columns() + static_cast<std::size_t>(column)] *= 180.0 / M_PI / shrink;
    }
  }
  const fs::path path = dir / "degrees.csv";
  io::WriteLog(path.string(), log);
  return path;
}

TEST(Plausibility, EveryCommandRefusesAClampedBeamInDegreesUnderSixDegrees) {
  const auto dir = FreshDirectory("checks_degrees");
  // Divided by 5: the largest angle is 1.2°, inside both joints' ranges read as rad.
  const fs::path log = ClampedBeamInDegrees(dir, 5.0);
  const std::string commands[] = {
      "correct --params " + kParams + " " + Quoted(log) + " -o out.csv",
      "filter --params " + kParams + " " + Quoted(log) + " -o out.csv",
      "identify " + Quoted(log) + " -o out.json",
      "diagnose --params " + kParams + " " + Quoted(log) + " -o report"};
  for (const auto& command : commands) {
    const auto r = RunCommand("cd " + Quoted(dir) + " && " + kCli + " " + command, dir);
    EXPECT_EQ(r.exit_code, 2) << command << "\n" << r.err;
    // K1 ≈ 0.068 rad/(N·m) on this log: 0.068·57.3/5 = 0.78.
    EXPECT_EQ(r.err.rfind(log.string() + ": joint 1: on the held-tip rows (tip_fixed = 1) q1 "
                                          "moves by 0.78",
                          0),
              0u)
        << r.err;
    EXPECT_NE(r.err.find("this looks like degrees; convert q1, q2"), std::string::npos);
    EXPECT_FALSE(fs::exists(dir / "out.csv") || fs::exists(dir / "out.json") ||
                 fs::exists(dir / "report"));
  }
}

TEST(Plausibility, TimeInMillisecondsIsRefusedAndAnHourLongGapWarned) {
  const auto dir = FreshDirectory("checks_time");
  std::ofstream ms(dir / "ms.csv"), gap(dir / "gap.csv");
  ms.precision(12), gap.precision(12);
  ms << "t,q1,q2,q3,tau1,tau2,v1,v2\n";
  gap << "t,q1,q2,q3,tau1,tau2\n";
  for (int i = 0; i < 200; ++i) {
    const double t = 0.01 * i;
    ms << 1000 * t << "," << 0.1 * std::sin(t) << ",0,0.1,0,0," << 0.1 * std::cos(t) << ",0\n";
    gap << t + (i >= 100 ? 3600.0 : 0.0) << ",0,0,0.1,0,0\n";
  }
  ms.close(), gap.close();
  const auto refused = RunCommand(kCli + " correct --params " + kParams + " " +
                                      Quoted(dir / "ms.csv") + " -o " + Quoted(dir / "o.csv"),
                                  dir);
  EXPECT_EQ(refused.exit_code, 2);
  EXPECT_EQ(refused.err, (dir / "ms.csv").string() +
                             ": q1 changes only 0.001 times as fast as v1 says (Δq/Δt against v1 "
                             "over the log): t looks like milliseconds \u2014 give t in seconds "
                             "(divide it by 1000)\n");
  const auto warned = RunCommand(kCli + " correct --params " + kParams + " " +
                                     Quoted(dir / "gap.csv") + " -o " + Quoted(dir / "o.csv"),
                                 dir);
  EXPECT_EQ(warned.exit_code, 0) << warned.err;
  EXPECT_NE(warned.err.find("warning: " + (dir / "gap.csv").string() +
                            ":102: t jumps by 3600 s (the median step is 0.01 s): two recordings "
                            "joined? Split the log, or give each part its own segment\n"),
            std::string::npos)
      << warned.err;
}

// Without a bias sweep the paper's procedure would keep the prior's bias
// table with no uncertainty (before: K1 +25 % at 48σ and a negative clearance,
// exit 0); it is refused, and nothing is written.
TEST(Identify, ThePapersMethodNeedsABiasSweep) {
  const auto dir = FreshDirectory("checks_paper_no_sweep");
  const auto r = RunCommand(kCli + " identify --method paper " + kSource +
                                "/data/clamped_beam.csv -o " + Quoted(dir / "p.json"),
                            dir);
  EXPECT_EQ(r.exit_code, 2) << r.err;
  EXPECT_NE(r.err.find("/data/clamped_beam.csv: the paper's procedure starts from a bias sweep "
                       "(rows with the tip free), and these logs have none for joint 1"),
            std::string::npos)
      << r.err;
  EXPECT_NE(r.err.find(" — add the bias-sweep log (e.g. data/bias_sweep.csv), or use --method "
                       "smoother"),
            std::string::npos)
      << r.err;
  EXPECT_FALSE(fs::exists(dir / "p.json"));
  // With the sweep it runs (and both clearances come out positive).
  const auto with = RunCommand(kCli + " identify --method paper " + kSource +
                                   "/data/bias_sweep.csv " + kSource + "/data/clamped_beam.csv -o " +
                                   Quoted(dir / "p.json"),
                               dir);
  ASSERT_EQ(with.exit_code, 0) << with.err;
  EXPECT_EQ(ReadText(dir / "p.json").find("\"value\": -"), std::string::npos);
}

TEST(Identify, ADivotLogAloneIsBadInputWithoutLibraryChatter) {
  const auto dir = FreshDirectory("checks_divot_identify");
  const auto r =
      RunCommand(kCli + " identify " + kSource + "/data/divot.csv -o " + Quoted(dir / "p.json"), dir);
  EXPECT_EQ(r.exit_code, 2) << r.err;
  EXPECT_EQ(r.err.find("Logging before InitGoogleLogging"), std::string::npos) << r.err;
  EXPECT_EQ(r.err.find("rank deficient"), std::string::npos) << r.err;
  // Which check the fit fails first depends on where it ends; the refusal does not.
  EXPECT_NE(r.err.find("/data/divot.csv: these logs do not determine the parameters: the fit "
                       "gives joint1: the compliance "),
            std::string::npos)
      << r.err;
  EXPECT_FALSE(fs::exists(dir / "p.json"));
}

struct OptionCase {
  const char* name;
  std::string arguments;
  std::string message;  // the whole of stderr
};

TEST(OptionError, ValuesThatWrapOrOverflowAreRefused) {
  const auto dir = FreshDirectory("checks_options");
  {
    std::ofstream huge(dir / "huge.json");
    std::string text = ReadText(kParams);
    const std::string cubic = "[639.16, -432.35, 136.32, 3.12]";
    text.replace(text.find(cubic), cubic.size(), "[1e308, 0, 0, 1]");
    huge << text;
  }
  const OptionCase cases[] = {
      {"seed", "simulate " + kSource + "/experiments/scenarios/clamped_beam.json --seed -1 -o x.csv",
       "--seed: the seed is a whole number from 0 to 2^64 - 1\nRun with --help for more "
       "information.\n"},
      {"max_lag", "diagnose --params " + kParams + " " + kSource + "/data/divot.csv --max-lag -1",
       "--max-lag: Value -1 not in range 0 to 100000\nRun with --help for more information.\n"},
      {"unloaded_start",
       "filter --params " + kParams + " " + kSource + "/data/divot.csv -o x.csv --unloaded-start 1e9",
       "--unloaded-start: unloaded_start_s = 1e+09 s is not shorter than the log, which lasts "
       "448.98 s \u2014 give the seconds at the log's start with the instrument untouched and the "
       "arm still, e.g. 0.1, or 0 for none\n"},
      {"directory_as_parameters", "params " + dir.string() + " --depth 0.1",
       dir.string() + ": is a directory, not a parameters file \u2014 give the path of a .json "
                      "file; data/paper.json is a complete example\n"},
      {"huge_compliance", "params " + (dir / "huge.json").string() + " --depth 0.1",
       (dir / "huge.json").string() +
           ":11:5: joint1: the compliance law gives K = 1.37174e-305 rad/(N·m) at L = 0.09 m; it "
           "must lie within [0.0001, 1] rad/(N·m) on the valid depth range (a PSM instrument's "
           "is 0.03–0.1) \u2014 correct the value (docs/parameters.md shows a complete file)\n"},
      {"did_you_mean", "filter --params " + kParams + " in.csv -o x.csv --smoth",
       "The following argument was not expected: --smoth\nRun with --help for more "
       "information.\npliant filter: unknown option '--smoth' \u2014 did you mean '--smooth'?\n"},
  };
  for (const OptionCase& c : cases) {
    const auto r = RunCommand("cd " + Quoted(dir) + " && " + kCli + " " + c.arguments, dir);
    EXPECT_EQ(r.exit_code, 2) << c.name;
    EXPECT_EQ(r.err, c.message) << c.name;
    EXPECT_FALSE(fs::exists(dir / "x.csv")) << c.name;
  }
}

TEST(OutputError, EveryCommandChecksItsDestinationFirst) {
  const auto dir = FreshDirectory("checks_destinations");
  std::ofstream(dir / "file") << "a file, not a directory\n";
  const std::string missing = (dir / "no").string();
  const std::string log = kSource + "/data/divot.csv";
  const std::string commands[] = {
      "correct --params " + kParams + " " + log + " -o " + missing + "/x.csv",
      "filter --params " + kParams + " " + log + " -o " + missing + "/x.csv",
      "identify " + log + " -o " + missing + "/x.json",
      "simulate " + kSource + "/experiments/scenarios/clamped_beam.json -o " + missing + "/x.csv",
      "params " + kParams + " --dvrk-out " + missing + "/x.json"};
  for (const auto& command : commands) {
    const auto r = RunCommand(kCli + " " + command, dir);
    EXPECT_EQ(r.exit_code, 2) << command << r.err;
    EXPECT_NE(r.err.find(": the directory " + missing + " does not exist \u2014 create it first "
                         "(mkdir -p " + missing + ") or write elsewhere\n"),
              std::string::npos)
        << command << r.err;
  }
  // Report directories are created, but not inside a file: no raw filesystem error.
  const std::string inside_file = (dir / "file" / "report").string();
  for (const std::string& command :
       {"diagnose --params " + kParams + " " + log + " -o " + inside_file,
        "montecarlo " + kSource + "/experiments/studies/divot_study.json -o " + inside_file}) {
    const auto r = RunCommand(kCli + " " + command, dir);
    EXPECT_EQ(r.exit_code, 2) << command << r.err;
    EXPECT_EQ(r.err, "-o " + inside_file + ": " + (dir / "file").string() +
                         " is not a directory \u2014 give a path inside a directory\n")
        << command;
  }
}

TEST(Params, ReadsWritesAndComparesTheDvrksOwnFile) {
  const auto dir = FreshDirectory("checks_dvrk_params");
  const auto read = RunCommand(kCli + " params " + kDvrkFile + " --depth 0.15", dir);
  ASSERT_EQ(read.exit_code, 0) << read.err;
  EXPECT_EQ(read.out.rfind(kDvrkFile + ": the dVRK's compensation file (mtsPSMCompensation)", 0), 0u);
  // K1(0.15) = 0.043811825, K2(0.15) = 0.0261563375 from the file's cubics.
  EXPECT_NE(read.out.find("joint 1  K = 0.04381 ± 0.00000"), std::string::npos) << read.out;
  EXPECT_NE(read.out.find("joint 2  K = 0.02616 ± 0.00000"), std::string::npos) << read.out;

  const auto write =
      RunCommand(kCli + " params " + kDvrkFile + " --dvrk-out " + Quoted(dir / "out.json"), dir);
  ASSERT_EQ(write.exit_code, 0) << write.err;
  const std::string text = ReadText(dir / "out.json");
  EXPECT_NE(text.find("\"parameter\": \"compliance_first\",\n            \"value-a\": -38.3402,"),
            std::string::npos)
      << text;

  const auto compare = RunCommand(
      kCli + " params " + kParams + " --depth 0.15 --compare " + Quoted(dir / "out.json"), dir);
  ASSERT_EQ(compare.exit_code, 0) << compare.err;
  // The paper's K1(0.15) = 1/(639.16·0.15³ − 432.35·0.15² + 136.32·0.15 + 3.12) = 0.0625106.
  EXPECT_NE(compare.out.find("  K1             0.0625106 ± 0           0.0438118 ± 0       0.0187  σ "
                             "unknown\n"),
            std::string::npos)
      << compare.out;
}

}  // namespace
}  // namespace pliant
