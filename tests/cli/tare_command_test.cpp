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

}  // namespace
}  // namespace pliant::testing
