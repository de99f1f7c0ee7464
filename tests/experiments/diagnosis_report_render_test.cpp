// The report's plots render in a real browser: headless Chromium (Debian's
// `chromium`) loads the HTML, the page counts the images it decoded and laid
// out, and a screenshot of it carries far more than a blank page's.
#include <unistd.h>

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <regex>

#include "diagnosis_report_example.h"
#include "pliant/experiments/diagnosis_report.h"
#include "pliant/experiments/plot.h"
#include "run_command.h"

namespace pliant::experiments {
namespace {

namespace fs = std::filesystem;

std::string Chromium() {
  for (const char* path : {"/usr/bin/chromium", "/usr/bin/chromium-browser"}) {
    if (access(path, X_OK) == 0) return path;
  }
  return "";
}

// One headless run with its own profile (tests may run in parallel); as root
// Chromium needs --no-sandbox.
std::string ChromiumCommand(const fs::path& dir, const std::string& what, const fs::path& page) {
  return Chromium() + " --headless=new --no-sandbox --disable-gpu --no-first-run" +
         " --user-data-dir='" + (dir / "profile").string() + "' --virtual-time-budget=5000 " +
         what + " 'file://" + page.string() + "'";
}

TEST(DiagnosisReportInChromium, EveryPlotRendersAndTheScreenshotIsNotBlank) {
  if (Chromium().empty()) GTEST_SKIP() << "chromium is not installed (apt-get install chromium)";
  if (FindGnuplot().empty()) GTEST_SKIP() << "gnuplot is not installed";
  const auto dir = testing::FreshDirectory("diagnosis_report_render");
  const auto log = testing::ExampleLog();
  const auto files = WriteDiagnosisReport((dir / "report").string(), log,
                                          testing::ExampleDiagnosis(log), {"log.csv", "p.json"});
  ASSERT_EQ(files.figures.size(), 4u);

  const auto dom = testing::RunCommand(ChromiumCommand(dir, "--dump-dom", files.html), dir);
  ASSERT_EQ(dom.exit_code, 0) << dom.err;
  std::smatch found;
  ASSERT_TRUE(std::regex_search(
      dom.out, found,
      std::regex("id=\"render-check\" data-expected=\"(\\d+)\" data-rendered=\"(\\d+)\"")))
      << dom.out.substr(0, 2000);
  EXPECT_EQ(found[1], "4");
  EXPECT_EQ(found[2], "4") << "plots the browser decoded and laid out";

  // A blank page of the same size is the baseline for "not blank".
  const fs::path blank = dir / "blank.html";
  std::ofstream(blank) << "<!DOCTYPE html><html><body></body></html>\n";
  auto screenshot = [&](const fs::path& page, const fs::path& png) {
    const auto shot = testing::RunCommand(
        ChromiumCommand(dir, "--window-size=1200,2000 --screenshot='" + png.string() + "'", page),
        dir);
    EXPECT_EQ(shot.exit_code, 0) << shot.err;
    return fs::exists(png) ? fs::file_size(png) : 0;
  };
  const auto blank_bytes = screenshot(blank, dir / "blank.png");
  const auto report_bytes = screenshot(files.html, dir / "report.png");
  ASSERT_GT(blank_bytes, 0u);
  EXPECT_GT(report_bytes, 10 * blank_bytes)
      << "report " << report_bytes << " B, blank " << blank_bytes << " B";
}

}  // namespace
}  // namespace pliant::experiments
