// The report for a first reader: a picture gnuplot cannot draw is a warning,
// not a failure; the NIS row says whether it is inside its band; channels at
// the edge of the lag window or that are the log's time get a remark; the
// worst-segment panel is shown only where the effect changes something; the
// --add effects appear with their fitted values; size is explained.
#include <gtest/gtest.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>

#include "diagnosis_report_example.h"
#include "pliant/experiments/diagnosis_report.h"
#include "run_command.h"

namespace pliant::experiments {
namespace {

namespace fs = std::filesystem;
using testing::ExampleDiagnosis;
using testing::ExampleLog;

// A gnuplot that always fails, as gnuplot does on "all points y value undefined".
struct FailingGnuplot {
  explicit FailingGnuplot(const fs::path& dir) : script(dir / "gnuplot") {
    std::ofstream(script) << "#!/bin/sh\necho 'all points y value undefined' >&2\nexit 1\n";
    fs::permissions(script, fs::perms::owner_all);
    const char* old = std::getenv("PLIANT_GNUPLOT");
    if (old) previous = old;
    setenv("PLIANT_GNUPLOT", script.c_str(), 1);
  }
  ~FailingGnuplot() {
    if (previous.empty()) unsetenv("PLIANT_GNUPLOT");
    else setenv("PLIANT_GNUPLOT", previous.c_str(), 1);
  }
  fs::path script;
  std::string previous;
};

TEST(DiagnosisReportReader, AFailingPictureIsListedAndTheReportStillWritten) {
  const auto dir = testing::FreshDirectory("report_failing_gnuplot");
  const FailingGnuplot gnuplot(dir);
  const auto log = ExampleLog();
  const auto files = WriteDiagnosisReport((dir / "report").string(), log, ExampleDiagnosis(log),
                                          {"log.csv", "p.json"});
  EXPECT_TRUE(files.figures.empty());
  ASSERT_EQ(files.missing_figures.size(), 4u);
  EXPECT_NE(files.missing_figures[0].find("residual_time.png"), std::string::npos);
  const std::string html = testing::ReadText(files.html);
  EXPECT_NE(html.find("A picture is missing: residual_time.png"), std::string::npos);
  EXPECT_TRUE(fs::exists(files.summary_json));
}

// A joint with no compared row (a one-joint log) has an all-NaN residual: its
// panels are left out instead of handing gnuplot a plot with no point.
TEST(DiagnosisReportReader, AJointWithNoResidualGetsNoPanelAndNoFailure) {
  const auto dir = testing::FreshDirectory("report_one_joint");
  const auto log = ExampleLog();
  auto d = ExampleDiagnosis(log);
  for (auto* series : {&d.series.residual_before_rad[1], &d.series.residual_after_rad[1]})
    for (double& r : *series) r = NAN;
  std::vector<std::string> missing;
  const auto drawn = WriteDiagnosisFigures((dir / "figures").string(), log, d, &missing);
  EXPECT_TRUE(missing.empty()) << missing.front();
  EXPECT_EQ(drawn.size(), 4u);
}

TEST(DiagnosisReportReader, TheNisRowHasAVerdict) {
  const auto log = ExampleLog();
  auto d = ExampleDiagnosis(log);
  d.before.mean_nis = 9.5;
  d.before.nis_band[0] = 0.9, d.before.nis_band[1] = 1.1;
  const std::string above = DiagnosisReportHtml(log, d, {"log.csv", "p.json"}, {});
  EXPECT_NE(above.find("above its band"), std::string::npos);
  d.before.mean_nis = 0.5;
  EXPECT_NE(DiagnosisReportHtml(log, d, {"log.csv", "p.json"}, {}).find("below its band"),
            std::string::npos);
  d.before.mean_nis = 1.0;
  EXPECT_EQ(DiagnosisSummaryJson(d)["before"]["nis_verdict"],
            "inside its band: the filter's noise model fits these rows");
}

TEST(DiagnosisReportReader, ChannelRemarksAndAddedEffectsAreShown) {
  const auto log = ExampleLog();
  auto d = ExampleDiagnosis(log);
  d.channels[2].remark = "the log's time: a slow drift";
  estimation::EffectFinding added;
  added.name = "joint_friction";
  added.parameter_names = {"coulomb1"};
  added.parameters = {0.0512};
  added.parameter_sd = {0.0016};
  d.added = {added};
  d.added_effects = {"joint_friction"};
  const std::string html = DiagnosisReportHtml(log, d, {"log.csv", "p.json"}, {});
  EXPECT_NE(html.find("Note: the log"), std::string::npos);
  EXPECT_NE(html.find("0.0512 ± 0.0016"), std::string::npos);
  const auto j = DiagnosisSummaryJson(d);
  ASSERT_EQ(j["added"].size(), 1u);
  EXPECT_DOUBLE_EQ(j["added"][0]["parameters"][0]["value"].get<double>(), 0.0512);
  EXPECT_DOUBLE_EQ(j["added"][0]["parameters"][0]["sd"].get<double>(), 0.0016);
  EXPECT_EQ(j["channels"][2]["remark"], "the log's time: a slow drift");
}

// The worst-segment panel shows a segment only where before and after differ.
TEST(DiagnosisReportReader, NoWorstSegmentFigureWhenTheEffectChangesNothing) {
  const auto dir = testing::FreshDirectory("report_no_difference");
  const auto log = ExampleLog();
  auto d = ExampleDiagnosis(log);
  for (int j = 0; j < 2; ++j) d.series.residual_after_rad[j] = d.series.residual_before_rad[j];
  const auto drawn = WriteDiagnosisFigures((dir / "same").string(), log, d);
  for (const auto& path : drawn)
    EXPECT_EQ(path.find("worst_segment"), std::string::npos) << path;
  const auto changed =
      WriteDiagnosisFigures((dir / "changed").string(), log, ExampleDiagnosis(log));
  EXPECT_NE(changed.back().find("worst_segment"), std::string::npos);
}

}  // namespace
}  // namespace pliant::experiments
