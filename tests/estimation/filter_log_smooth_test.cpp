// `pliant filter --smooth` (FilterLog with smooth, the checkpointed pass of
// smoothed_pass.h) writes FilterSmoother's estimates to the bit: on the
// shipped divot push (over 12,000 rows: a dozen blocks of 1024) with the motor
// inertia aligned (held samples at the log's end).
#include <cmath>
#include <filesystem>
#include <fstream>
#include <string>

#include <gtest/gtest.h>

#include "../support/paper_parameters.h"
#include "pliant/estimation/filter_log.h"
#include "pliant/estimation/filter_smoother.h"
#include "pliant/io/input_error.h"
#include "pliant/io/log.h"
#include "run_command.h"

namespace pliant::estimation {
namespace {

const std::string kPush = std::string(PLIANT_SOURCE_DIR) + "/data/divot_push.csv";

TEST(FilterLogSmooth, WritesFilterSmoothersEstimatesToTheBit) {
  const auto parameters = models::testing::PaperParameters();
  FilterOptions options;
  options.motor_inertia_kg_m2 = 0.08;  // the simulator's arm
  options.align_inertial_torque = true;
  ASSERT_GT(ComplianceFilter(parameters, options).alignment_steps(), 0);
  const auto dir = pliant::testing::FreshDirectory("filter_log_smooth");
  const auto out = (dir / "smoothed.csv").string();
  const LogFilterSummary summary = FilterLog(kPush, out, parameters, options, true, "test");

  const io::Log input = io::ReadLog(kPush);
  const io::StandardColumns columns(input.header);
  FilterSmoother smoother(parameters, options);
  for (std::size_t r = 0; r < input.Rows(); ++r) {
    smoother.Add(SampleFromRow(columns, &input.values[r * input.Columns()], options.fuse_log_reference));
  }
  smoother.Smooth();
  const io::Log log = io::ReadLog(out);
  ASSERT_EQ(log.Rows(), input.Rows());
  ASSERT_GT(log.Rows(), 10000u);
  EXPECT_EQ(summary.rows, log.Rows());
  const int q1 = log.header.Index("q1_corr"), q2 = log.header.Index("q2_corr");
  const int sd1 = log.header.Index("q1_sd"), tip = log.header.Index("tip_corr_mm");
  const int nis = log.header.Index("nis"), flags = log.header.Index("flags");
  double largest_step = 0.0;
  for (std::size_t r = 0; r < log.Rows(); ++r) {
    const FilterEstimate e = smoother.Estimate(r);
    const double* row = &log.values[r * log.Columns()];
    ASSERT_EQ(row[q1], e.corrected_rad[0]) << "row " << r;
    ASSERT_EQ(row[q2], e.corrected_rad[1]) << "row " << r;
    ASSERT_EQ(row[sd1], std::sqrt(e.covariance_rad2(0, 0))) << "row " << r;
    ASSERT_EQ(row[tip], e.tip_correction_mm) << "row " << r;
    ASSERT_EQ(row[nis], e.nis) << "row " << r;
    ASSERT_EQ(row[flags], double(e.flags)) << "row " << r;
    if (r > 0) largest_step = std::max(largest_step, std::abs(row[q1] - log.values[(r - 1) * log.Columns() + q1]));
  }
  EXPECT_GT(largest_step, 0.0);
  // The smoothed tip error is over every row against the reference.
  EXPECT_EQ(summary.smoothed_error.count(), summary.filtered.count());
}

// A bad row deep in the log (after several blocks' worth of rows) is found on
// the forward pass: an InputError naming its line, and no output written;
// skipped when asked, and counted (the summary's skipped_rows).
TEST(FilterLogSmooth, ABadRowLeavesNoOutput) {
  const auto dir = pliant::testing::FreshDirectory("filter_log_smooth_bad");
  const auto bad = (dir / "bad.csv").string(), out = (dir / "out.csv").string();
  {
    std::ifstream in(kPush);
    std::ofstream copy(bad);
    std::string line;
    for (int n = 1; std::getline(in, line); ++n) {
      if (n == 5000) line.erase(0, line.find(','));  // no t
      copy << line << "\n";
    }
  }
  try {
    FilterLog(bad, out, models::testing::PaperParameters(), FilterOptions{}, true, "test");
    ADD_FAILURE() << "no error";
  } catch (const io::InputError& e) {
    EXPECT_NE(std::string(e.what()).find("bad.csv:5000"), std::string::npos) << e.what();
  }
  EXPECT_FALSE(std::filesystem::exists(out));
  // Under skip_bad_rows the row is dropped, counted, and the rest smoothed.
  io::LogReaderOptions skip;
  skip.skip_bad_rows = true;
  const LogFilterSummary s =
      FilterLog(bad, out, models::testing::PaperParameters(), FilterOptions{}, true, "test", skip);
  EXPECT_EQ(s.skipped_rows, 1u);
  EXPECT_EQ(s.rows + 1, io::ReadLog(kPush).Rows());
  EXPECT_EQ(io::ReadLog(out).Rows(), s.rows);
}

}  // namespace
}  // namespace pliant::estimation
