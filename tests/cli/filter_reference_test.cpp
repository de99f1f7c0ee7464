// A log's q*_ref columns (an optical tracker's tip angles) score the filter's
// output and are fused only with `--fuse-reference SD`, SD the tracker's own
// noise: fused with a σ it does not have, the tracker is rejected on most rows.
#include <gtest/gtest.h>

#include <cmath>
#include <random>
#include <string>
#include <vector>

#include "pliant/io/log_reader.h"
#include "pliant/io/log_writer.h"
#include "run_command.h"

namespace pliant::testing {
namespace {

const std::string kCli = PLIANT_CLI;
const std::string kSource = PLIANT_SOURCE_DIR;
constexpr double kTrackerNoiseRad = 3e-4;  // a tracker's tip angle, 0.3 mrad

// data/divot_push.csv with q1_ref, q2_ref = q*_true + tracker noise on its held rows.
std::string WriteWithTracker(const std::filesystem::path& dir) {
  io::Log log = io::ReadLog(kSource + "/data/divot_push.csv");
  const int truth[2] = {log.header.Index("q1_true"), log.header.Index("q2_true")};
  const int fixed = log.header.Index("tip_fixed");
  const std::size_t columns_before = log.Columns(), rows = log.Rows();
  const int ref[2] = {log.header.AddColumn("q1_ref"), log.header.AddColumn("q2_ref")};
  std::vector<double> values;
  for (std::size_t r = 0; r < rows; ++r) {
    for (std::size_t c = 0; c < columns_before; ++c) values.push_back(log.values[r * columns_before + c]);
    values.resize(values.size() + log.Columns() - columns_before, NAN);
  }
  std::mt19937_64 rng(7);
  std::normal_distribution<double> noise(0.0, kTrackerNoiseRad);
  for (std::size_t r = 0; r < rows; ++r) {
    double* row = &values[r * log.Columns()];
    if (row[fixed] < 0.5) continue;
    for (int j = 0; j < 2; ++j) row[ref[j]] = row[truth[j]] + noise(rng);
  }
  log.values = values;
  const auto path = (dir / "with_tracker.csv").string();
  io::WriteLog(path, log);
  return path;
}

struct FilterRun {
  std::vector<double> q1_corr, flags;
};

FilterRun Filter(const std::string& options, const std::string& input, const std::filesystem::path& dir,
           const std::string& name) {
  const auto out = (dir / name).string();
  const auto r = RunCommand(kCli + " filter " + options + " --params " + kSource +
                                "/data/paper.json " + input + " -o " + out,
                            dir);
  EXPECT_EQ(r.exit_code, 0) << r.err;
  const io::Log log = io::ReadLog(out);
  return {log.Column("q1_corr"), log.Column("flags")};
}

std::size_t Rejected(const FilterRun& run) {
  std::size_t n = 0;
  for (double f : run.flags) n += (static_cast<int>(f) & 1) != 0;
  return n;
}

TEST(FilterReference, ATrackerColumnScoresTheOutputAndIsFusedOnlyWhenAsked) {
  const auto dir = FreshDirectory("filter_reference");
  const std::string tracked = WriteWithTracker(dir);
  const FilterRun without = Filter("", kSource + "/data/divot_push.csv", dir, "without.csv");
  const FilterRun scored = Filter("", tracked, dir, "scored.csv");
  ASSERT_EQ(scored.q1_corr.size(), without.q1_corr.size());
  for (std::size_t r = 0; r < without.q1_corr.size(); ++r) {
    ASSERT_EQ(scored.q1_corr[r], without.q1_corr[r]) << "row " << r;
  }
  // Fused with the tracker's own σ it changes the output and is rarely gated;
  // with a σ six times too small (5e-5 rad) it is rejected on many more rows.
  const FilterRun fused = Filter("--fuse-reference 3e-4", tracked, dir, "fused.csv");
  const FilterRun overconfident = Filter("--fuse-reference 5e-5", tracked, dir, "overconfident.csv");
  std::size_t changed = 0;
  for (std::size_t r = 0; r < fused.q1_corr.size(); ++r) changed += fused.q1_corr[r] != without.q1_corr[r];
  EXPECT_GT(changed, fused.q1_corr.size() / 10);
  EXPECT_LT(Rejected(fused), Rejected(without) + fused.q1_corr.size() / 50);
  EXPECT_GT(Rejected(overconfident), Rejected(fused) + fused.q1_corr.size() / 10);
}

}  // namespace
}  // namespace pliant::testing
