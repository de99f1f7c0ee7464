// What a log's header tells the filter (FilterLog): a joint the log does not
// record keeps its prior and its output columns are empty, and a quasi-static
// log's t is a pose index only: no dynamics are read from it. The shipped real
// clamped-beam log of joint 1 (data/real/) is both.
#include <cmath>
#include <string>

#include <gtest/gtest.h>

#include "../support/paper_parameters.h"
#include "pliant/estimation/filter_log.h"
#include "pliant/io/log.h"
#include "pliant/io/log_writer.h"
#include "run_command.h"

namespace pliant::estimation {
namespace {

const std::string kClampedJoint1 = std::string(PLIANT_SOURCE_DIR) + "/data/real/jhu2017_clamped_j1.csv";

TEST(FilterLogHeader, AnUnrecordedJointKeepsItsPriorAndItsColumnsAreEmpty) {
  const auto dir = pliant::testing::FreshDirectory("filter_log_header_unrecorded");
  const auto out = (dir / "out.csv").string();
  const LogFilterSummary s =
      FilterLog(kClampedJoint1, out, models::testing::PaperParameters(), FilterOptions{}, false, "test");
  EXPECT_EQ(s.missing_rows, 0u);  // the unrecorded joint is not "missing" on every row
  ASSERT_EQ(s.notes.size(), 2u);
  EXPECT_NE(s.notes[1].find("joint 2 not recorded"), std::string::npos);
  const io::Log log = io::ReadLog(out);
  const int q1 = log.header.Index("q1_corr"), q2 = log.header.Index("q2_corr");
  const int sd2 = log.header.Index("q2_sd"), cov = log.header.Index("q12_cov");
  const std::size_t w = log.header.columns.size();
  ASSERT_GT(log.Rows(), 900u);
  for (std::size_t r = 0; r < log.Rows(); ++r) {
    EXPECT_TRUE(std::isfinite(log.values[r * w + q1]));
    EXPECT_TRUE(std::isnan(log.values[r * w + q2]));
    EXPECT_TRUE(std::isnan(log.values[r * w + sd2]));
    EXPECT_TRUE(std::isnan(log.values[r * w + cov]));
  }
  EXPECT_NE(log.header.Metadata("filter").find("joint 2 not recorded"), std::string::npos);
}

TEST(FilterLogHeader, AQuasiStaticLogReadsNoDynamicsFromItsPoseIndex) {
  // The same rows with t = 1000 × the pose index, and with the rows 1 µs apart:
  // a filter that read dynamics (process noise per second, rates) from t
  // would differ between the two.
  const auto dir = pliant::testing::FreshDirectory("filter_log_header_quasi_static");
  io::Log log = io::ReadLog(kClampedJoint1);
  const std::size_t w = log.header.columns.size();
  const int t = log.header.Index("t");
  io::Log slow = log, fast = log;
  for (std::size_t r = 0; r < log.Rows(); ++r) {
    slow.values[r * w + t] = 1000.0 * double(r);
    fast.values[r * w + t] = 1e-6 * double(r);
  }
  const auto p = models::testing::PaperParameters();
  std::string corrected[2];
  int k = 0;
  for (const io::Log* in : {&slow, &fast}) {
    const auto in_path = (dir / ("in" + std::to_string(k) + ".csv")).string();
    const auto out_path = (dir / ("out" + std::to_string(k) + ".csv")).string();
    io::WriteLog(in_path, *in);
    const LogFilterSummary s = FilterLog(in_path, out_path, p, FilterOptions{}, false, "test");
    EXPECT_EQ(s.notes.size(), 2u);
    const io::Log out = io::ReadLog(out_path);
    const int q1 = out.header.Index("q1_corr");
    for (std::size_t r = 0; r < out.Rows(); ++r) {
      corrected[k] += std::to_string(out.values[r * out.header.columns.size() + q1]) + ",";
    }
    ++k;
  }
  EXPECT_EQ(corrected[0], corrected[1]);
}

}  // namespace
}  // namespace pliant::estimation
