// A `pliant correct` or `pliant filter` killed midway (SIGKILL: no destructor,
// no cleanup) leaves the old output or none — never a torn file, never a stray
// temporary.
#include <fcntl.h>
#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <filesystem>
#include <fstream>
#include <set>
#include <thread>

#include <gtest/gtest.h>

#include "pliant/io/log_reader.h"
#include "pliant/io/log_writer.h"
#include "run_command.h"

namespace pliant {
namespace {

namespace fs = std::filesystem;

void WriteLongLog(const fs::path& path, std::size_t rows) {
  io::LogHeader header;
  header.columns = {"t", "q1", "q2", "q3", "tau1", "tau2"};
  io::LogWriter writer(path.string(), header);
  for (std::size_t i = 0; i < rows; ++i) {
    const double row[] = {i / 1500.0, 0.1 + 1e-7 * double(i % 1000), -0.2, 0.15, 0.7, -0.4};
    writer.Write(row);
  }
  writer.Commit();
}

// Starts `pliant <command>`, lets it run for `delay`, then kills it.
void RunAndKill(const char* command, const fs::path& dir, std::chrono::milliseconds delay) {
  const std::string params = std::string(PLIANT_SOURCE_DIR) + "/data/paper.json";
  const std::string in = (dir / "in.csv").string(), out = (dir / "out.csv").string();
  const pid_t child = testing::StartPliantSilently({command, "--params", params, in, "-o", out});
  ASSERT_GE(child, 0);
  std::this_thread::sleep_for(delay);
  testing::KillAndReap(child);
}

std::set<std::string> Files(const fs::path& dir) {
  std::set<std::string> names;
  for (const auto& entry : fs::directory_iterator(dir)) names.insert(entry.path().filename());
  return names;
}

class KillDuring : public ::testing::TestWithParam<const char*> {};

TEST_P(KillDuring, LeavesTheOldOutputAndNoTemporary) {
  const fs::path dir = testing::FreshDirectory(std::string("kill_") + GetParam());
  WriteLongLog(dir / "in.csv", 400000);  // 0.4 s (correct) to 1.2 s (filter) of work
  for (int delay_ms : {5, 50, 150}) {
    std::ofstream(dir / "out.csv") << "precious\n";
    RunAndKill(GetParam(), dir, std::chrono::milliseconds(delay_ms));
    const std::string out = testing::ReadText(dir / "out.csv");
    if (out != "precious\n") {  // it finished before the kill: then it is whole
      EXPECT_EQ(io::ReadLog((dir / "out.csv").string()).Rows(), 400000u) << delay_ms;
    }
    EXPECT_EQ(Files(dir), (std::set<std::string>{"in.csv", "out.csv"}))
        << "after a kill at " << delay_ms << " ms";
  }
}

TEST_P(KillDuring, WithoutAnOldOutputLeavesNothing) {
  const fs::path dir = testing::FreshDirectory(std::string("kill_new_") + GetParam());
  WriteLongLog(dir / "in.csv", 400000);
  RunAndKill(GetParam(), dir, std::chrono::milliseconds(50));
  const auto files = Files(dir);
  if (files.count("out.csv")) {
    EXPECT_EQ(io::ReadLog((dir / "out.csv").string()).Rows(), 400000u);
  }
  for (const auto& name : files) {
    EXPECT_EQ(name.find(".tmp"), std::string::npos) << name;
  }
}

INSTANTIATE_TEST_SUITE_P(Commands, KillDuring, ::testing::Values("correct", "filter"),
                         [](const auto& info) { return std::string(info.param); });

}  // namespace
}  // namespace pliant
