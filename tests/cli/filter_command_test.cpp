// pliant filter on the shipped sample: columns, summary, smoothing, errors.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <random>
#include <string>
#include <utility>
#include <vector>

#include "pliant/io/log_reader.h"
#include "pliant/io/log_writer.h"
#include "run_command.h"

namespace pliant::testing {
namespace {

const std::string kCli = PLIANT_CLI;
const std::string kSource = PLIANT_SOURCE_DIR;

TEST(FilterCommand, AddsTheFilterColumnsAndBeatsEquation2OnTheSample) {
  const auto dir = FreshDirectory("filter_command");
  const auto out = (dir / "out.csv").string();
  const auto r = RunCommand(kCli + " filter --params " + kSource + "/data/paper.json " + kSource +
                                "/data/divot_push.csv -o " + out,
                            dir);
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_NE(r.out.find("pliant filter: 12313 rows -> " + out), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("uncorrected          RMS   5.717 mm"), std::string::npos) << r.out;
  const io::Log log = io::ReadLog(out);
  for (const char* column : {"q1_corr", "q2_corr", "q1_sd", "q2_sd", "q12_cov", "tip_corr_mm",
                             "tip_corr_sd_mm", "nis", "flags", "contact_probability"}) {
    EXPECT_TRUE(log.header.Has(column)) << column;
  }
  // Equation (2) on this log: RMS 1.041 mm (docs/correction.md). The filter
  // with a fixed tip must do far better; read its RMS from the summary.
  const auto at = r.out.find("filter               RMS");
  ASSERT_NE(at, std::string::npos) << r.out;
  const double rms = std::stod(r.out.substr(at + 25, 8));
  EXPECT_LT(rms, 0.3 * 1.041);
  const auto sd = log.Column("q1_sd");
  for (double v : sd) ASSERT_TRUE(std::isfinite(v) && v > 0.0);
}

TEST(FilterCommand, SmoothsWhenAsked) {
  const auto dir = FreshDirectory("filter_command_smooth");
  const auto out = (dir / "out.csv").string();
  const auto r = RunCommand(kCli + " filter --smooth --params " + kSource + "/data/paper.json " +
                                kSource + "/data/divot_push.csv -o " + out,
                            dir);
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_NE(r.out.find("RTS smoothed"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("smoother             RMS"), std::string::npos) << r.out;
}

// `pliant filter` on the divot push log, with the defaults and with FLAG:
// `column` of each run. `directory` is the calling test's own: ctest runs the
// tests of this file in parallel.
std::pair<std::vector<double>, std::vector<double>> ColumnWithAndWithout(
    const std::string& flag, const std::string& column, const std::string& directory) {
  const auto dir = FreshDirectory(directory);
  const std::string args = " --params " + kSource + "/data/paper.json " + kSource +
                           "/data/divot_push.csv -o ";
  const auto plain = (dir / "plain.csv").string(), flagged = (dir / "flagged.csv").string();
  EXPECT_EQ(RunCommand(kCli + " filter" + args + plain, dir).exit_code, 0);
  const auto r = RunCommand(kCli + " filter " + flag + args + flagged, dir);
  EXPECT_EQ(r.exit_code, 0) << r.err;
  auto a = io::ReadLog(plain).Column(column), b = io::ReadLog(flagged).Column(column);
  EXPECT_EQ(a.size(), b.size());
  return {a, b};
}

// How many rows of `column` FLAG changes (out of how many).
std::pair<std::size_t, std::size_t> RowsAFlagChanges(const std::string& flag,
                                                     const std::string& column,
                                                     const std::string& directory) {
  const auto [a, b] = ColumnWithAndWithout(flag, column, directory);
  std::size_t differ = 0;
  for (std::size_t i = 0; i < std::min(a.size(), b.size()); ++i) differ += a[i] != b[i];
  return {differ, a.size()};
}

// --no-held-load-bound reaches the filter: the held rows' q1_sd differ from
// the default's (the load's process variance is another), the rest of the run not.
TEST(FilterCommand, TheHeldLoadBoundCanBeTurnedOff) {
  const auto [differ, rows] =
      RowsAFlagChanges("--no-held-load-bound", "q1_sd", "filter_command_held_bound");
  EXPECT_GT(differ, rows / 10);
}

// `pliant filter FLAG` with a bad value: exit 2, the option's field named,
// nothing written.
void ExpectRejected(const std::string& flag, const std::string& field,
                    const std::string& directory) {
  const auto dir = FreshDirectory(directory);
  const auto out = (dir / "out.csv").string();
  const auto bad = RunCommand(kCli + " filter " + flag + " --params " + kSource +
                                  "/data/paper.json " + kSource + "/data/divot_push.csv -o " + out,
                              dir);
  EXPECT_EQ(bad.exit_code, 2);
  EXPECT_NE(bad.err.find(field), std::string::npos) << bad.err;
  EXPECT_FALSE(std::filesystem::exists(out));
}

// The damping term acts on held rows whose encoder moves with the shaft on its
// wall: the corrected angles change there; a negative damping is bad input.
TEST(FilterCommand, TheShaftDampingReachesTheFilter) {
  const auto [differ, rows] =
      RowsAFlagChanges("--shaft-damping 0.02", "q1_corr", "filter_command_damping_flag");
  EXPECT_GT(differ, rows / 10);
  ExpectRejected("--shaft-damping -1", "shaft_damping_nm_s_per_rad", "filter_command_damping");
}

// ε is encoder noise in proportion to the deflection: 0.2 instead of the
// default 0.08 (no damping given) widens q1_sd on every row of the divot push,
// the median by 2.15× (measured); a negative ε is bad input.
TEST(FilterCommand, TheDeflectionErrorWidensTheIntervals) {
  auto [a, b] =
      ColumnWithAndWithout("--deflection-error 0.2", "q1_sd", "filter_command_deflection_flag");
  ASSERT_EQ(a.size(), b.size());
  std::size_t narrower = 0;
  for (std::size_t i = 0; i < a.size(); ++i) narrower += b[i] < a[i];
  EXPECT_EQ(narrower, 0u);
  const auto median = [](std::vector<double>& v) {
    std::nth_element(v.begin(), v.begin() + v.size() / 2, v.end());
    return v[v.size() / 2];
  };
  EXPECT_GT(median(b) / median(a), 1.8);
  ExpectRejected("--deflection-error -1", "deflection_model_error",
                 "filter_command_deflection_bad");
}

// --no-load-following reaches the filter: a held load that no longer follows
// the motor changes the corrected angles of the push's held rows. The
// inertial torque's error κ is a share of J·θ̈: without --motor-inertia
// (J = 0) no row changes; a negative κ is bad input.
TEST(FilterCommand, TheHeldLoadModelAndTheInertialErrorReachTheFilter) {
  const auto [differ, rows] =
      RowsAFlagChanges("--no-load-following", "q1_corr", "filter_command_load_following");
  EXPECT_GT(differ, rows / 10);
  const auto [inertial, all] =
      RowsAFlagChanges("--inertial-error 2", "q1_sd", "filter_command_inertial_error");
  EXPECT_EQ(inertial, 0u);
  EXPECT_GT(all, 1000u);
  ExpectRejected("--inertial-error -1", "--inertial-error", "filter_command_inertial_bad");
}

// --unloaded-start tares the effort offset (turning β on): the sample log's
// arm rests untouched for its first 3 s, and the corrected angles change from
// there on; a negative span is bad input.
TEST(FilterCommand, AnUnloadedStartReachesTheFilter) {
  const auto [differ, rows] =
      RowsAFlagChanges("--unloaded-start 0.15", "q1_corr", "filter_command_unloaded_start");
  EXPECT_GT(differ, rows / 2);
  ExpectRejected("--unloaded-start -1", "--unloaded-start: unloaded_start_s",
                 "filter_command_unloaded_bad");
}

// The shipped push with three times its effort noise (0.01 N·m more than
// doubled: 0.03 added): the summary says what the efforts hold, and with
// --effort-noise-from-log the filter takes it and rejects fewer rows.
TEST(FilterCommand, TheEffortNoiseIsReadFromTheLogWhenAsked) {
  const auto dir = FreshDirectory("filter_command_noise");
  io::Log log = io::ReadLog(kSource + "/data/divot_push.csv");
  std::mt19937 rng(3);
  std::normal_distribution<double> noise(0.0, 0.03);
  const auto tau1 = std::size_t(log.header.Index("tau1"));
  const auto tau2 = std::size_t(log.header.Index("tau2"));
  for (std::size_t r = 0; r < log.Rows(); ++r) {
    log.values[r * log.Columns() + tau1] += noise(rng);
    log.values[r * log.Columns() + tau2] += noise(rng);
  }
  const auto noisy = (dir / "noisy.csv").string();
  io::WriteLog(noisy, log);
  const auto run = [&](const std::string& flag) {
    const auto r = RunCommand(kCli + " filter " + flag + " --params " + kSource +
                                  "/data/paper.json " + noisy + " -o " + (dir / "out.csv").string(),
                              dir);
    EXPECT_EQ(r.exit_code, 0) << r.err;
    const auto at = r.out.find("rejected ");
    return std::make_pair(r.out, at == std::string::npos ? -1L : std::stol(r.out.substr(at + 9)));
  };
  const auto [assumed, assumed_rejected] = run("");
  const auto [taken, taken_rejected] = run("--effort-noise-from-log");
  // √(0.01² + 0.03²) = 0.0316 N·m, within the estimator's spread (a few %).
  EXPECT_NE(assumed.find("the efforts hold 0.03"), std::string::npos) << assumed;
  EXPECT_NE(assumed.find("--effort-noise-from-log uses it"), std::string::npos) << assumed;
  EXPECT_NE(taken.find("N·m: used"), std::string::npos) << taken;
  EXPECT_GT(assumed_rejected, 0);
  EXPECT_LT(taken_rejected, assumed_rejected / 10);
}

TEST(FilterCommand, BadInputExitsTwoAndWritesNothing) {
  const auto dir = FreshDirectory("filter_command_bad");
  const auto out = dir / "out.csv";
  const auto r = RunCommand(kCli + " filter --params " + kSource + "/data/paper.json " +
                                (dir / "missing.csv").string() + " -o " + out.string(),
                            dir);
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_NE(r.err.find("cannot open the log"), std::string::npos) << r.err;
  EXPECT_FALSE(std::filesystem::exists(out));
}

}  // namespace
}  // namespace pliant::testing
