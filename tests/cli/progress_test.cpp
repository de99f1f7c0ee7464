// Progress on a terminal, silence when piped or with --quiet: the decision is
// tested with a real pseudo-terminal as standard error, not by timing.
#include <fcntl.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cerrno>
#include <cstdlib>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "run_command.h"

namespace pliant {
namespace {

using testing::FreshDirectory;
using testing::RunCommand;

const std::string kParams = std::string(PLIANT_SOURCE_DIR) + "/data/paper.json";
const std::string kPush = std::string(PLIANT_SOURCE_DIR) + "/data/divot_push.csv";

struct TerminalRun {
  int exit_code = -1;
  std::string terminal;  ///< what the command wrote to its standard error, a terminal
};

// Runs pliant with standard error on a new pseudo-terminal (standard output to
// /dev/null) and returns everything written to the terminal.
TerminalRun RunOnTerminal(const std::vector<std::string>& args) {
  TerminalRun run;
  const int master = ::posix_openpt(O_RDWR | O_NOCTTY);
  if (master < 0 || ::grantpt(master) != 0 || ::unlockpt(master) != 0) return run;
  const std::string slave_name = ::ptsname(master);
  const pid_t child = ::fork();
  if (child == 0) {
    ::setsid();
    const int slave = ::open(slave_name.c_str(), O_RDWR);
    const int null = ::open("/dev/null", O_WRONLY);
    ::dup2(null, STDOUT_FILENO);
    ::dup2(slave, STDERR_FILENO);
    ::close(master);
    std::vector<char*> argv{const_cast<char*>(PLIANT_CLI)};
    for (const std::string& a : args) argv.push_back(const_cast<char*>(a.c_str()));
    argv.push_back(nullptr);
    ::execv(PLIANT_CLI, argv.data());
    ::_exit(127);
  }
  // Read until every copy of the slave is closed (EIO), then reap.
  char buffer[4096];
  for (;;) {
    const ssize_t got = ::read(master, buffer, sizeof buffer);
    if (got > 0) {
      run.terminal.append(buffer, static_cast<std::size_t>(got));
    } else if (got < 0 && errno == EINTR) {
      continue;
    } else {
      break;
    }
  }
  int status = 0;
  ::waitpid(child, &status, 0);
  ::close(master);
  run.exit_code = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
  return run;
}

TEST(Progress, ShownOnATerminal) {
  const auto dir = FreshDirectory("progress_terminal");
  const auto run = RunOnTerminal({"filter", "--params", kParams, kPush, "-o",
                                  (dir / "out.csv").string()});
  ASSERT_EQ(run.exit_code, 0) << run.terminal;
  EXPECT_NE(run.terminal.find("pliant filter:"), std::string::npos) << run.terminal;
  EXPECT_NE(run.terminal.find("reading " + kPush + ": ["), std::string::npos) << run.terminal;
  EXPECT_NE(run.terminal.find("elapsed"), std::string::npos) << run.terminal;
  // The line is erased at the end, so nothing of it is left before the next output.
  EXPECT_NE(run.terminal.find("\r\033[K"), std::string::npos);
}

TEST(Progress, QuietOnATerminalWithQuiet) {
  const auto dir = FreshDirectory("progress_quiet");
  const auto run = RunOnTerminal({"filter", "--quiet", "--params", kParams, kPush, "-o",
                                  (dir / "out.csv").string()});
  ASSERT_EQ(run.exit_code, 0) << run.terminal;
  EXPECT_EQ(run.terminal, "");
}

TEST(Progress, QuietWhenStandardErrorIsNotATerminal) {
  const auto dir = FreshDirectory("progress_piped");
  const auto result = RunCommand(std::string(PLIANT_CLI) + " filter --params " + kParams + " " +
                                     kPush + " -o " + (dir / "out.csv").string(),
                                 dir);
  ASSERT_EQ(result.exit_code, 0) << result.err;
  EXPECT_EQ(result.err, "");
}

}  // namespace
}  // namespace pliant
