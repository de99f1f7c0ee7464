#pragma once
// What the error-message tests share: the command, a good log, and the check
// that a refused command left no output or temporary behind.
#include <filesystem>
#include <fstream>
#include <string>

#include <gtest/gtest.h>

#include "run_command.h"

namespace pliant::errors_test {

namespace fs = std::filesystem;
using pliant::testing::CommandResult;
using pliant::testing::FreshDirectory;
using pliant::testing::ReadText;
using pliant::testing::RunCommand;

inline const std::string kCli = PLIANT_CLI;
inline const std::string kSource = PLIANT_SOURCE_DIR;
inline const std::string kParams = kSource + "/data/paper.json";
inline const std::string kGoodLog = "t,q1,q2,q3,tau1,tau2\n0,0,0,0.1,0,0\n0.01,0,0,0.1,0.1,0\n";

inline void WriteText(const fs::path& path, const std::string& text) {
  std::ofstream(path, std::ios::binary) << text;
}

inline std::string Quoted(const fs::path& path) { return "'" + path.string() + "'"; }

// Neither the output nor a temporary of it exists in `dir`.
inline void ExpectNothingWritten(const fs::path& dir, const std::string& output) {
  EXPECT_FALSE(fs::exists(dir / output)) << output << " was written";
  for (const auto& entry : fs::directory_iterator(dir)) {
    EXPECT_EQ(entry.path().filename().string().find(".tmp"), std::string::npos)
        << "temporary file left: " << entry.path();
  }
}

}  // namespace pliant::errors_test
