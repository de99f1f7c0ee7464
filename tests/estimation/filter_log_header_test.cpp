// What a log's header tells the filter (FilterLog): a joint the log does not
// record keeps its prior and its output columns are empty, and a quasi-static
// log's t is a pose index only: no dynamics are read from it. The shipped real
// clamped-beam log of joint 1 (data/real/) is both.
#include <algorithm>
#include <cmath>
#include <filesystem>
#include <string>
#include <vector>

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

// The corrected joint 1 of FilterLog on `log`, written to DIR/NAME.
std::vector<double> CorrectedJoint1(const io::Log& log, const std::filesystem::path& dir,
                                    const std::string& name, LogFilterSummary* summary) {
  const auto in_path = (dir / (name + ".csv")).string();
  const auto out_path = (dir / (name + "_out.csv")).string();
  io::WriteLog(in_path, log);
  *summary = FilterLog(in_path, out_path, models::testing::PaperParameters(), FilterOptions{},
                       false, "test");
  const io::Log out = io::ReadLog(out_path);
  return out.Column("q1_corr");
}

TEST(FilterLogHeader, RowsFurtherApartThanATimeGapArePoses) {
  // The real clamped beam without its "# timing: quasi-static" line and t a
  // pose index (1 s apart), as another tool would write it: filtered as the
  // marked log is, and the summary says why. The same rows 10 ms apart are a
  // continuous log.
  const auto dir = pliant::testing::FreshDirectory("filter_log_header_spacing");
  const io::Log marked = io::ReadLog(kClampedJoint1);
  io::Log unmarked = marked, continuous = marked;
  for (io::Log* log : {&unmarked, &continuous}) {
    auto& m = log->header.metadata;
    m.erase(std::remove_if(m.begin(), m.end(), [](const auto& kv) { return kv.first == "timing"; }),
            m.end());
  }
  const std::size_t w = marked.header.columns.size();
  const int t = marked.header.Index("t");
  for (std::size_t r = 0; r < marked.Rows(); ++r) {
    unmarked.values[r * w + t] = double(r);
    continuous.values[r * w + t] = 0.01 * double(r);
  }
  LogFilterSummary s_marked, s_unmarked, s_continuous;
  const auto a = CorrectedJoint1(marked, dir, "marked", &s_marked);
  const auto b = CorrectedJoint1(unmarked, dir, "unmarked", &s_unmarked);
  CorrectedJoint1(continuous, dir, "continuous", &s_continuous);
  ASSERT_EQ(a.size(), b.size());
  for (std::size_t r = 0; r < a.size(); ++r) EXPECT_DOUBLE_EQ(a[r], b[r]) << "row " << r;
  ASSERT_FALSE(s_unmarked.notes.empty());
  EXPECT_NE(s_unmarked.notes[0].find("median 1 s apart"), std::string::npos) << s_unmarked.notes[0];
  EXPECT_EQ(s_marked.notes[0].find("apart"), std::string::npos) << s_marked.notes[0];
  for (const auto& note : s_continuous.notes) EXPECT_EQ(note.find("quasi-static"), std::string::npos);
}

TEST(FilterLogHeader, MedianRowSpacingIsTheMiddleStepOfTheFirstRows) {
  EXPECT_DOUBLE_EQ(MedianRowSpacing({0.0, 1.0, 2.0, 3.0, 10.0}), 1.0);  // steps 1, 1, 1, 7
  EXPECT_DOUBLE_EQ(MedianRowSpacing({0.0, 0.5, 0.6, 2.0}), 0.5);        // steps 0.5, 0.1, 1.4
  EXPECT_TRUE(std::isnan(MedianRowSpacing({0.0, 1.0, 2.0})));          // two steps: too few
  std::vector<double> times(100);
  for (std::size_t i = 0; i < times.size(); ++i) times[i] = i < 21 ? 0.01 * double(i) : 5.0 * double(i);
  EXPECT_NEAR(MedianRowSpacing(times), 0.01, 1e-12);  // only the first 21 rows decide
}

}  // namespace
}  // namespace pliant::estimation
