// The real clamped beam (JHU 2017, data/real/README.md), cross-validated over
// depths as /work/shared/tools/clamped_cv.py does: identify from both bias
// sweeps and every other depth of both clamped logs, then correct and filter
// the other depths with nothing that says where the tip is (no tip_fixed, no
// reference); and the other way round. The tip is clamped, so the truth is
// constant within a depth: the score is the mean over depths of the standard
// deviation of the corrected angle. Issue 25's goal: ≤ 2.0 mrad per joint.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <map>
#include <set>
#include <string>
#include <vector>

#include "pliant/io/log_reader.h"
#include "pliant/io/log_writer.h"
#include "run_command.h"

namespace pliant {
namespace {

namespace fs = std::filesystem;
using testing::FreshDirectory;
using testing::RunCommand;

const std::string kCli = PLIANT_CLI;
const std::string kReal = PLIANT_SOURCE_DIR "/data/real/";

// The depth bin of each row (5 mm of q3), as clamped_cv.py.
std::vector<long> DepthBins(const io::Log& log) {
  const int q3 = log.header.Index("q3");
  std::vector<long> bins;
  for (std::size_t r = 0; r < log.Rows(); ++r) bins.push_back(std::lround(log.Value(r, q3) / 0.005));
  return bins;
}

// The depths of one parity (0: the first, third, … depth), without the
// columns that say where the tip is when `blind`.
void WriteHalf(const io::Log& log, int parity, bool blind, const fs::path& out) {
  const std::vector<long> bins = DepthBins(log);
  const std::set<long> distinct(bins.begin(), bins.end());
  const std::vector<long> levels(distinct.begin(), distinct.end());
  std::set<long> keep;
  for (size_t i = 0; i < levels.size(); ++i) {
    if (int(i % 2) == parity) keep.insert(levels[i]);
  }
  const std::set<std::string> hidden = {"tip_fixed", "q1_ref", "q2_ref", "q1_true", "q2_true"};
  io::Log half;
  half.header.metadata = log.header.metadata;
  half.header.joint_recorded = log.header.joint_recorded;
  std::vector<std::size_t> columns;
  for (std::size_t c = 0; c < log.Columns(); ++c) {
    if (blind && hidden.count(log.header.columns[c])) continue;
    columns.push_back(c);
    half.header.columns.push_back(log.header.columns[c]);
  }
  for (std::size_t r = 0; r < log.Rows(); ++r) {
    if (!keep.count(bins[r])) continue;
    for (std::size_t c : columns) half.values.push_back(log.Value(r, c));
  }
  io::WriteLog(out.string(), half);
}

// The standard deviation of q<joint>_corr per depth of an output, rad.
std::vector<double> SpreadPerDepth(const fs::path& output, int joint) {
  const io::Log log = io::ReadLog(output.string());
  const int col = log.header.Index("q" + std::to_string(joint) + "_corr");
  EXPECT_GE(col, 0);
  const std::vector<long> bins = DepthBins(log);
  std::map<long, std::vector<double>> by_depth;
  for (std::size_t r = 0; r < log.Rows(); ++r) {
    const double q = log.Value(r, std::size_t(col));
    if (std::isfinite(q)) by_depth[bins[r]].push_back(q);
  }
  std::vector<double> spreads;
  for (const auto& [bin, q] : by_depth) {
    if (q.size() <= 5) continue;
    double mean = 0.0, square = 0.0;
    for (double v : q) mean += v / q.size();
    for (double v : q) square += (v - mean) * (v - mean) / q.size();
    spreads.push_back(std::sqrt(square));
  }
  return spreads;
}

// Mean spread over the held-out depths of both halves, mrad, per joint.
struct Score {
  double joint_mrad[2] = {0.0, 0.0};
};

std::map<std::string, Score> CrossValidate(const fs::path& dir,
                                           const std::vector<std::string>& commands) {
  const io::Log clamped[2] = {io::ReadLog(kReal + "jhu2017_clamped_j1.csv"),
                              io::ReadLog(kReal + "jhu2017_clamped_j2.csv")};
  std::map<std::string, std::vector<double>> spreads[2];
  for (int parity = 0; parity < 2; ++parity) {
    std::string train;
    for (int j = 0; j < 2; ++j) {
      const fs::path path = dir / ("train_j" + std::to_string(j + 1) + ".csv");
      WriteHalf(clamped[j], parity, false, path);
      train += " '" + path.string() + "'";
    }
    const std::string params = (dir / "params.json").string();
    const auto identified = RunCommand(kCli + " identify --quiet '" + kReal +
                                           "jhu2017_bias_j1.csv' '" + kReal +
                                           "jhu2017_bias_j2.csv'" + train + " -o '" + params + "'",
                                       dir);
    EXPECT_EQ(identified.exit_code, 0) << identified.err;
    for (int j = 0; j < 2; ++j) {
      const fs::path test = dir / ("test_j" + std::to_string(j + 1) + ".csv");
      WriteHalf(clamped[j], 1 - parity, true, test);
      for (const std::string& command : commands) {
        const fs::path out = dir / "out.csv";
        const auto r = RunCommand(kCli + " " + command + " --quiet --params '" + params + "' '" +
                                      test.string() + "' -o '" + out.string() + "'",
                                  dir);
        EXPECT_EQ(r.exit_code, 0) << r.err;
        for (double s : SpreadPerDepth(out, j + 1)) spreads[j][command].push_back(s);
      }
    }
  }
  std::map<std::string, Score> scores;
  for (const std::string& command : commands) {
    for (int j = 0; j < 2; ++j) {
      const auto& s = spreads[j][command];
      EXPECT_EQ(s.size(), 14u) << command << " joint " << j + 1;
      double sum = 0.0;
      for (double v : s) sum += v;
      scores[command].joint_mrad[j] = 1e3 * sum / std::max<size_t>(1, s.size());
    }
  }
  return scores;
}

TEST(RealClampedBeam, TheFilterHoldsTheHeldTipAsCorrectDoes) {
  const fs::path dir = FreshDirectory("real_clamped_cv");
  auto scores = CrossValidate(dir, {"correct", "filter"});
  // Measured: correct 1.52 / 1.48 mrad; filter 1.83 / 1.52 (each quasi-static
  // row its own draw of the contact chain: 2.35 / 1.74).
  for (int j = 0; j < 2; ++j) {
    EXPECT_LE(scores["filter"].joint_mrad[j], 2.0) << "joint " << j + 1;
    EXPECT_LE(scores["filter"].joint_mrad[j], scores["correct"].joint_mrad[j] + 0.4)
        << "joint " << j + 1;
  }
}

}  // namespace
}  // namespace pliant
