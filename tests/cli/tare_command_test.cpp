// --tare in pliant correct and pliant filter: one tare (estimation/log_tare.h)
// on the sample divot-push log whose efforts are shifted by a known constant,
// as a bias torque drifted since calibration shifts them.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include "pliant/io/log_reader.h"
#include "run_command.h"

namespace pliant::testing {
namespace {

const std::string kCli = PLIANT_CLI;
const std::string kSource = PLIANT_SOURCE_DIR;
const std::string kParams = kSource + "/data/paper.json";
const std::string kLog = kSource + "/data/divot_push.csv";
constexpr double kShiftNm[2] = {0.08, -0.05};  // the drift: added to tau1, tau2

// The sample log with kShiftNm added to its tau1 and tau2 columns.
std::string ShiftedLog(const std::filesystem::path& dir) {
  std::ifstream in(kLog);
  const auto path = (dir / "shifted.csv").string();
  std::ofstream out(path);
  std::string line;
  int tau[2] = {-1, -1};
  while (std::getline(in, line)) {
    if (line.empty() || line[0] == '#' || tau[0] < 0) {
      if (!line.empty() && line[0] != '#') {  // the header row
        std::vector<std::string> names;
        std::istringstream fields(line);
        for (std::string f; std::getline(fields, f, ',');) names.push_back(f);
        for (int j = 0; j < 2; ++j) {
          tau[j] = int(std::find(names.begin(), names.end(), "tau" + std::to_string(j + 1)) -
                       names.begin());
        }
      }
      out << line << '\n';
      continue;
    }
    std::istringstream fields(line);
    std::string f, row;
    for (int c = 0; std::getline(fields, f, ','); ++c) {
      for (int j = 0; j < 2; ++j) {
        if (c != tau[j]) continue;
        char buffer[40];
        std::snprintf(buffer, sizeof buffer, "%.17g", std::stod(f) + kShiftNm[j]);
        f = buffer;
      }
      row += (c == 0 ? "" : ",") + f;
    }
    out << row << '\n';
  }
  return path;
}

double MaxDifference(const std::string& a, const std::string& b, const std::string& column) {
  const auto x = io::ReadLog(a).Column(column), y = io::ReadLog(b).Column(column);
  EXPECT_EQ(x.size(), y.size());
  double worst = 0.0;
  for (std::size_t i = 0; i < std::min(x.size(), y.size()); ++i) {
    worst = std::max(worst, std::abs(x[i] - y[i]));
  }
  return worst;
}

// The offset and σ the output states for joint j ("bias offset +0.0799 ± 0.0003 N·m").
std::pair<double, double> StatedOffset(const std::string& out, int joint) {
  const auto line = out.find("tare joint " + std::to_string(joint));
  const auto at = out.find("bias offset ", line);
  EXPECT_NE(at, std::string::npos) << out;
  if (at == std::string::npos) return {NAN, NAN};
  const double offset = std::stod(out.substr(at + 12));
  const auto pm = out.find("± ", at);
  return {offset, std::stod(out.substr(pm + std::string("± ").size()))};
}

const char* kDisagree = "disagree with the parameters' bias beyond its σ";

TEST(CorrectTare, TaresTheShiftAwayAndSaysSo) {
  const auto dir = FreshDirectory("tare_correct");
  const auto shifted = ShiftedLog(dir);
  const auto tared = (dir / "tared.csv").string(), plain = (dir / "plain.csv").string();
  const auto r = RunCommand(kCli + " correct --tare auto --params " + kParams + " " + shifted +
                                " -o " + tared,
                            dir);
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_NE(r.out.find("tare joint 1: 848 unloaded rows (t 22.93 to 31.4): bias offset +0.0799 "
                       "± 0.0003 N·m"),
            std::string::npos)
      << r.out;
  EXPECT_NE(r.out.find("tare joint 2: 1612 unloaded rows (t 67.1 to 83.21): bias offset -0.0499 "
                       "± 0.0003 N·m"),
            std::string::npos)
      << r.out;
  EXPECT_NE(r.out.find(kDisagree), std::string::npos) << r.out;
  // The same rows of the unshifted log: the offsets differ by the shift
  // exactly, so the corrected joints are the same to rounding.
  const auto r0 = RunCommand(kCli + " correct --tare auto --params " + kParams + " " + kLog +
                                 " -o " + plain,
                             dir);
  ASSERT_EQ(r0.exit_code, 0) << r0.err;
  EXPECT_EQ(r0.out.find(kDisagree), std::string::npos) << r0.out;
  EXPECT_LT(MaxDifference(tared, plain, "q1_corr"), 1e-12);
  EXPECT_LT(MaxDifference(tared, plain, "q2_corr"), 1e-12);
}

// The filter tared on the shifted log runs the tared parameters: it recovers
// the shift within the σ it states, and its corrected joints are those of the
// filter on the unshifted log with the parameters' own (true) bias.
TEST(FilterTare, RecoversAKnownShiftAndFiltersAsWithTheTrueBias) {
  const auto dir = FreshDirectory("tare_filter");
  const auto shifted = ShiftedLog(dir);
  const auto tared = (dir / "tared.csv").string(), truth = (dir / "truth.csv").string(),
             untared = (dir / "untared.csv").string();
  const std::string params = " --params " + kParams + " ";
  const auto r = RunCommand(kCli + " filter --tare auto" + params + shifted + " -o " + tared, dir);
  ASSERT_EQ(r.exit_code, 0) << r.err;
  for (int j = 1; j <= 2; ++j) {
    const auto [offset, sd] = StatedOffset(r.out, j);
    EXPECT_GT(sd, 0.0);
    EXPECT_LE(std::abs(offset - kShiftNm[j - 1]), 2.0 * sd) << r.out;
  }
  EXPECT_NE(r.out.find(kDisagree), std::string::npos) << r.out;
  EXPECT_NE(io::ReadLog(tared).header.Metadata("filter").find("bias tared on the log: joint 1 "
                                                              "+0.0799 ± 0.0003 N·m"),
            std::string::npos);
  ASSERT_EQ(RunCommand(kCli + " filter" + params + kLog + " -o " + truth, dir).exit_code, 0);
  ASSERT_EQ(RunCommand(kCli + " filter" + params + shifted + " -o " + untared, dir).exit_code, 0);
  // Untared, the shift moves the corrected joints by up to 15 mrad (joint 1);
  // tared, they stay within 0.3 mrad of the true bias's (0.01 mrad but where a
  // contact begins: the tare's 0.3 mN·m doubt moves the row the contact chain
  // believes it by one or two, 0.19 mrad on joint 1).
  EXPECT_GT(MaxDifference(untared, truth, "q1_corr"), 1e-2);
  EXPECT_LT(MaxDifference(tared, truth, "q1_corr"), 3e-4);
  EXPECT_LT(MaxDifference(tared, truth, "q2_corr"), 3e-4);
}

// On the unshifted log the tare finds noise (±0.0003 N·m) and says nothing of
// a disagreement; the filter on the shifted and the unshifted log, both
// tared, is the same filter to rounding (one tared model).
TEST(FilterTare, NoDisagreementWithoutAShiftAndTheSameModelEitherWay) {
  const auto dir = FreshDirectory("tare_filter_plain");
  const auto shifted = ShiftedLog(dir);
  const auto a = (dir / "a.csv").string(), b = (dir / "b.csv").string();
  const std::string params = " --tare auto --params " + kParams + " ";
  const auto r = RunCommand(kCli + " filter" + params + kLog + " -o " + a, dir);
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_NE(r.out.find("tare joint 1: 848 unloaded rows"), std::string::npos) << r.out;
  EXPECT_EQ(r.out.find(kDisagree), std::string::npos) << r.out;
  ASSERT_EQ(RunCommand(kCli + " filter" + params + shifted + " -o " + b, dir).exit_code, 0);
  EXPECT_LT(MaxDifference(a, b, "q1_corr"), 1e-12);
  EXPECT_LT(MaxDifference(a, b, "q2_corr"), 1e-12);
}

// Bad --tare input: exit 2, FILE:… — …, and an existing output untouched.
void ExpectRefused(const std::string& command, const std::string& message,
                   const std::string& directory) {
  const auto dir = FreshDirectory(directory);
  const auto out = (dir / "out.csv").string();
  { std::ofstream(out) << "keep me\n"; }
  const auto r = RunCommand(command + " -o " + out, dir);
  EXPECT_EQ(r.exit_code, 2) << r.err;
  EXPECT_NE(r.err.find(message), std::string::npos) << r.err;
  EXPECT_EQ(ReadText(out), "keep me\n");
}

TEST(FilterTare, RefusesARangeWithNoRowsStandardInputAndUnloadedStart) {
  const std::string params = " --params " + kParams + " ";
  for (const char* command : {"filter", "correct"}) {
    ExpectRefused(kCli + " " + command + " --tare 500:600" + params + kLog,
                  kLog + ": --tare 500:600 names no row: its t runs from 0 to 123.12 s — name a "
                         "time range inside it, or write --tare auto",
                  std::string("tare_range_") + command);
    ExpectRefused("cat " + kLog + " | " + kCli + " " + command + " --tare auto" + params + "-",
                  "--tare: the tare reads the log before the command does, and standard input can "
                  "be read only once — give the log as a file, or leave out --tare",
                  std::string("tare_stdin_") + command);
    ExpectRefused(kCli + " " + command + " --tare 1:x" + params + kLog,
                  "--tare: '1:x' is neither auto nor T0:T1", std::string("tare_spec_") + command);
  }
  ExpectRefused(kCli + " filter --tare auto --unloaded-start 0.1" + params + kLog,
                "--unloaded-start excludes --tare", "tare_unloaded_start");
}

}  // namespace
}  // namespace pliant::testing
