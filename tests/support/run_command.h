#pragma once
// Runs a command in a shell and captures its exit status, stdout and stderr.
#include <fcntl.h>
#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

namespace pliant::testing {

struct CommandResult {
  int exit_code = -1;
  std::string out;
  std::string err;
};

inline std::string ReadText(const std::filesystem::path& path) {
  std::ifstream in(path, std::ios::binary);
  std::ostringstream text;
  text << in.rdbuf();
  return text.str();
}

inline CommandResult RunCommand(const std::string& command, const std::filesystem::path& dir) {
  const auto out = dir / "stdout.txt";
  const auto err = dir / "stderr.txt";
  const int status =
      std::system((command + " >'" + out.string() + "' 2>'" + err.string() + "'").c_str());
  CommandResult result;
  result.exit_code = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
  result.out = ReadText(out);
  result.err = ReadText(err);
  return result;
}

/// Starts `pliant args…` in the background with its output discarded; returns
/// its pid (for the kill tests: SIGKILL means no destructor and no cleanup).
inline pid_t StartPliantSilently(const std::vector<std::string>& args) {
  const pid_t child = fork();
  if (child != 0) return child;
  const int null = ::open("/dev/null", O_WRONLY);
  dup2(null, 1);
  dup2(null, 2);
  std::vector<char*> argv{const_cast<char*>(PLIANT_CLI)};
  for (const std::string& a : args) argv.push_back(const_cast<char*>(a.c_str()));
  argv.push_back(nullptr);
  execv(PLIANT_CLI, argv.data());
  _exit(127);
}

/// SIGKILLs a child and reaps it; returns its wait status.
inline int KillAndReap(pid_t child) {
  kill(child, SIGKILL);
  int status = 0;
  waitpid(child, &status, 0);
  return status;
}

/// A fresh, empty directory for one test.
inline std::filesystem::path FreshDirectory(const std::string& name) {
  // The process id keeps two test runs on one machine (two build trees, two
  // checkouts) out of each other's directories.
  const auto dir = std::filesystem::temp_directory_path() /
                   ("pliant_test_" + name + "_" + std::to_string(::getpid()));
  std::filesystem::remove_all(dir);
  std::filesystem::create_directories(dir);
  return dir;
}

/// Runs `command` with `dir` as the working directory, its output kept there.
inline CommandResult RunIn(const std::filesystem::path& dir, const std::string& command) {
  return RunCommand("cd '" + dir.string() + "' && " + command, dir);
}

}  // namespace pliant::testing
