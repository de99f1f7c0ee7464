#include "pliant/io/input_error.h"

#include <gtest/gtest.h>

namespace pliant::io {
namespace {

TEST(InputError, FormatsFileLineColumnProblemAndFix) {
  const InputError error("run.csv", 12, 3, "value 'x' is not a number", "write a number");
  EXPECT_STREQ(error.what(), "run.csv:12:3: value 'x' is not a number \u2014 write a number");
  EXPECT_EQ(error.file(), "run.csv");
  EXPECT_EQ(error.line(), 12u);
  EXPECT_EQ(error.column(), 3u);
  EXPECT_EQ(error.problem(), "value 'x' is not a number");
  EXPECT_EQ(error.fix(), "write a number");
}

TEST(InputError, LeavesOutUnknownColumn) {
  const InputError error("run.csv", 7, 0, "problem", "fix");
  EXPECT_STREQ(error.what(), "run.csv:7: problem \u2014 fix");
}

TEST(InputError, LeavesOutUnknownLineAndColumn) {
  EXPECT_STREQ(InputError("run.csv", 0, 0, "problem", "fix").what(), "run.csv: problem \u2014 fix");
  // A column without a line means nothing to an editor: both are left out.
  EXPECT_STREQ(InputError("run.csv", 0, 4, "problem", "fix").what(), "run.csv: problem \u2014 fix");
}

TEST(InputError, DashIsEmDashBetweenSpaces) {
  const std::string text = InputError("f", 1, 1, "p", "x").what();
  EXPECT_EQ(text, "f:1:1: p \xE2\x80\x94 x");
}

TEST(InputError, IsARuntimeError) {
  try {
    throw InputError("a.json", 2, 0, "p", "f");
  } catch (const std::runtime_error& error) {
    EXPECT_STREQ(error.what(), "a.json:2: p \u2014 f");
  }
}

}  // namespace
}  // namespace pliant::io
