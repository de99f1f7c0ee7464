// docs/errors.md and errors-runtime.md show real runs: every "$ build/cli/pliant …"
// line in their text blocks is run here, from a directory that sees the repository's data/,
// tests/ and experiments/, and its stderr and exit status must be exactly
// what the pages print after it (up to the "exit N" line). A message changed
// in the code without the page, or the page without the code, fails here.
#include <filesystem>
#include <sstream>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "run_command.h"

namespace pliant {
namespace {

namespace fs = std::filesystem;
using testing::FreshDirectory;
using testing::ReadText;
using testing::RunCommand;

const std::string kCli = PLIANT_CLI;
const std::string kSource = PLIANT_SOURCE_DIR;
const std::string kPrompt = "$ build/cli/pliant";

struct DocumentedRun {
  std::string arguments;  // after "pliant"
  std::string stderr_text;
  int exit_code = -1;
};

std::vector<DocumentedRun> RunsOf(const std::string& page) {
  std::vector<DocumentedRun> runs;
  std::istringstream in(page);
  std::string line;
  bool in_text = false;
  DocumentedRun* open = nullptr;
  while (std::getline(in, line)) {
    if (line.rfind("```", 0) == 0) {
      in_text = line == "```text";
      open = nullptr;
    } else if (in_text && line.rfind(kPrompt + " ", 0) == 0) {
      runs.push_back({line.substr(kPrompt.size()), "", -1});
      open = &runs.back();
    } else if (open != nullptr && line.rfind("exit ", 0) == 0) {
      open->exit_code = std::stoi(line.substr(5));
      open = nullptr;
    } else if (open != nullptr) {
      open->stderr_text += line + "\n";
    }
  }
  return runs;
}

TEST(ErrorsPage, EveryRealRunPrintsWhatThePageShows) {
  const auto runs = RunsOf(ReadText(kSource + "/docs/errors.md") +
                           ReadText(kSource + "/docs/errors-runtime.md"));
  ASSERT_GE(runs.size(), 8u) << "docs/errors.md and errors-runtime.md lost their real runs";
  const auto dir = FreshDirectory("errors_doc");
  for (const char* shared : {"data", "tests", "experiments"}) {
    fs::create_directory_symlink(fs::path(kSource) / shared, dir / shared);
  }
  for (const DocumentedRun& run : runs) {
    ASSERT_NE(run.exit_code, -1) << run.arguments << ": no 'exit N' line follows it";
#ifndef PLIANT_HAVE_ROS1
    // A pliant built without ROS 1 (the sanitizer build) answers every bag alike.
    if (run.arguments.find(".bag") != std::string::npos) continue;
#endif
    const auto r = RunCommand("cd '" + dir.string() + "' && " + kCli + run.arguments, dir);
    EXPECT_EQ(r.exit_code, run.exit_code) << run.arguments << "\n" << r.err;
    EXPECT_EQ(r.err, run.stderr_text) << run.arguments;
    EXPECT_FALSE(fs::exists(dir / "out.csv")) << run.arguments;
  }
}

}  // namespace
}  // namespace pliant
