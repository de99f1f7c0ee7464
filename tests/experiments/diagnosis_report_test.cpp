#include "pliant/experiments/diagnosis_report.h"

#include <gtest/gtest.h>

#include <boost/archive/iterators/binary_from_base64.hpp>
#include <boost/archive/iterators/transform_width.hpp>
#include <filesystem>
#include <iterator>

#include "diagnosis_report_example.h"
#include "pliant/estimation/effect_catalogue.h"
#include "pliant/experiments/plot.h"
#include "run_command.h"

namespace pliant::experiments {
namespace {

namespace fs = std::filesystem;
using testing::ExampleDiagnosis;
using testing::ExampleLog;

std::vector<std::string> Keys(const nlohmann::ordered_json& object, std::size_t n) {
  std::vector<std::string> keys;
  for (auto it = object.begin(); it != object.end() && keys.size() < n; ++it)
    keys.push_back(it.key());
  return keys;
}

TEST(DiagnosisSummaryJson, HasTheIssuesFieldsInOrderBestFirst) {
  const auto log = ExampleLog();
  const auto j = DiagnosisSummaryJson(ExampleDiagnosis(log));
  EXPECT_EQ(Keys(j, 5), (std::vector<std::string>{"rms_before", "rms_after", "missing_effect",
                                                  "effects", "channels"}));
  EXPECT_DOUBLE_EQ(j["rms_before"].get<double>(), 1.234);
  EXPECT_DOUBLE_EQ(j["rms_after"].get<double>(), 0.123);
  EXPECT_EQ(j["missing_effect"], "joint_friction");
  ASSERT_EQ(j["effects"].size(), 2u);
  EXPECT_EQ(Keys(j["effects"][0], 7),
            (std::vector<std::string>{"name", "description", "channels", "score", "p_value", "size",
                                      "size_sd"}));
  EXPECT_EQ(j["effects"][0]["name"], "joint_friction");
  EXPECT_EQ(j["effects"][0]["channels"], (nlohmann::ordered_json{"v1", "v2"}));
  EXPECT_DOUBLE_EQ(j["effects"][0]["score"].get<double>(), 0.9);
  EXPECT_DOUBLE_EQ(j["effects"][0]["size_sd"].get<double>(), 0.02);
  EXPECT_DOUBLE_EQ(j["effects"][0]["parameters"][1]["sd"].get<double>(), 0.0004);
  EXPECT_EQ(j["effects"][0]["parameters"][0]["at_bound"], false);
  EXPECT_EQ(j["effects"][1]["name"], "effort_drift");
  ASSERT_EQ(j["channels"].size(), 3u);
  EXPECT_EQ(Keys(j["channels"][0], 3), (std::vector<std::string>{"name", "lag", "score"}));
  EXPECT_EQ(j["channels"][1]["name"], "|tau1|");
  EXPECT_EQ(j["channels"][1]["lag"], 2);
}

TEST(DiagnosisSummaryJson, NoMissingEffectIsNull) {
  const auto log = ExampleLog();
  auto d = ExampleDiagnosis(log);
  d.missing_effect.reset();
  EXPECT_TRUE(DiagnosisSummaryJson(d)["missing_effect"].is_null());
}

// joint_friction's coulomb1 is bounded in the catalogue; a fit that ends on
// the bound is no estimate, and the report says so.
TEST(DiagnosisReport, AParameterOnItsCatalogueBoundIsMarked) {
  const auto log = ExampleLog();
  auto d = ExampleDiagnosis(log);
  const auto specs = estimation::EffectCatalogue::Global().Create("joint_friction")->Parameters();
  ASSERT_EQ(specs[2].name, "coulomb1");
  d.effects[0].parameters[0] = specs[2].upper_bound;
  EXPECT_EQ(DiagnosisSummaryJson(d)["effects"][0]["parameters"][0]["at_bound"], true);
  EXPECT_EQ(DiagnosisSummaryJson(d)["effects"][0]["parameters"][1]["at_bound"], false);
  const std::string html = DiagnosisReportHtml(log, d, {"log.csv", "p.json"}, {});
  ASSERT_EQ(specs[2].upper_bound, 1.0);
  EXPECT_NE(html.find("coulomb1 = 1 ± 0.002 <em>(at its bound)</em>"), std::string::npos);
  EXPECT_EQ(html.find("viscous1 = 0.001 ± 0.0004 <em>"), std::string::npos);
}

TEST(DiagnosisReportHtml, TablesCarryTheNumbersRankedAndEscaped) {
  const auto log = ExampleLog();
  const std::string html =
      DiagnosisReportHtml(log, ExampleDiagnosis(log), {"my log.csv", "p.json"}, {});
  EXPECT_NE(html.find("Missing effect: <strong><code>joint_friction</code>"), std::string::npos);
  EXPECT_NE(html.find("1.234 mm → 0.123 mm"), std::string::npos);
  EXPECT_NE(html.find("<td>1.000 / 0.000</td><td>0.100 / 0.000</td>"), std::string::npos)
      << "RMS per joint in mrad";
  EXPECT_NE(html.find("<td>90.0 %</td>"), std::string::npos);
  EXPECT_NE(html.find("coulomb1 = 0.05 ± 0.002"), std::string::npos);
  EXPECT_NE(html.find("0.87 ± 0.02 mm"), std::string::npos);
  EXPECT_NE(html.find("viscous &lt;and&gt; Coulomb"), std::string::npos);
  EXPECT_LT(html.find("<code>joint_friction</code> <strong"), html.find("<code>effort_drift"));
  EXPECT_LT(html.find("<code>sign(v1)</code>"), html.find("<code>|tau1|</code>"));
  EXPECT_NE(html.find("data-expected=\"0\""), std::string::npos);
}

std::string Decoded(const std::string& base64) {
  using namespace boost::archive::iterators;
  using Decoder = transform_width<binary_from_base64<std::string::const_iterator>, 8, 6>;
  std::string trimmed = base64;
  const std::size_t padding = trimmed.size() - trimmed.find_last_not_of('=') - 1;
  trimmed.erase(trimmed.size() - padding);
  std::string out(Decoder(trimmed.begin()), Decoder(trimmed.end()));
  return out.substr(0, (base64.size() / 4) * 3 - padding);
}

TEST(WriteDiagnosisReport, WritesSelfContainedHtmlSummaryAndFigures) {
  if (FindGnuplot().empty()) GTEST_SKIP() << "gnuplot is not installed";
  const auto dir = testing::FreshDirectory("diagnosis_report");
  const auto log = ExampleLog();
  const auto d = ExampleDiagnosis(log);
  const auto files = WriteDiagnosisReport((dir / "report").string(), log, d, {"log.csv", "p.json"});
  ASSERT_EQ(files.figures.size(), 4u);
  for (const auto& f : files.figures) EXPECT_GT(fs::file_size(f), 5000u) << f;
  EXPECT_EQ(nlohmann::ordered_json::parse(testing::ReadText(files.summary_json)),
            DiagnosisSummaryJson(d));
  const std::string html = testing::ReadText(files.html);
  EXPECT_NE(html.find("data-expected=\"4\""), std::string::npos);
  EXPECT_EQ(html.find("src=\"figures/"), std::string::npos) << "images must be embedded";
  // The first embedded image is figures/residual_time.png, byte for byte.
  const std::string marker = "data:image/png;base64,";
  const std::size_t start = html.find(marker) + marker.size();
  const std::string image = Decoded(html.substr(start, html.find('"', start) - start));
  EXPECT_EQ(image, testing::ReadText(files.figures[0]));
  EXPECT_EQ(fs::path(files.figures[0]).filename(), "residual_time.png");
  // No temporaries left beside the report.
  const auto entries = std::distance(fs::directory_iterator(dir / "report"), {});
  EXPECT_EQ(entries, 3) << "index.html, summary.json, figures/";
}

}  // namespace
}  // namespace pliant::experiments
