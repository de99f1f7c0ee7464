// `-` as an input reads standard input, `-o -` writes standard output, and an
// output that is a device is written through (docs/log-format.md "Pipes").
#include <sys/stat.h>

#include <filesystem>
#include <string>

#include <gtest/gtest.h>

#include "run_command.h"

namespace pliant {
namespace {

namespace fs = std::filesystem;
using testing::FreshDirectory;
using testing::ReadText;
using testing::RunCommand;

const std::string kCli = PLIANT_CLI;
const std::string kParams = std::string(PLIANT_SOURCE_DIR) + "/data/paper.json";
const std::string kPush = std::string(PLIANT_SOURCE_DIR) + "/data/divot_push.csv";

std::string Correct(const std::string& in, const std::string& out) {
  return kCli + " correct --params " + kParams + " " + in + " -o " + out;
}
std::string Filter(const std::string& in, const std::string& out, const std::string& extra = "") {
  return kCli + " filter --params " + kParams + " " + extra + " " + in + " -o " + out;
}

TEST(Pipes, CorrectFromStdinToStdoutGivesTheFileVersionsBytes) {
  const auto dir = FreshDirectory("pipes_correct");
  const auto file = RunCommand(Correct(kPush, (dir / "out.csv").string()), dir);
  ASSERT_EQ(file.exit_code, 0) << file.err;
  const auto piped = RunCommand("cat " + kPush + " | " + Correct("-", "-"), dir);
  ASSERT_EQ(piped.exit_code, 0) << piped.err;
  const std::string expected = ReadText(dir / "out.csv");
  ASSERT_GT(expected.size(), 100000u);
  EXPECT_TRUE(piped.out == expected) << "stdout differs from the file (" << piped.out.size()
                                     << " bytes against " << expected.size() << ")";
  // The summary moves to stderr so that stdout holds the log alone.
  EXPECT_NE(piped.err.find("pliant correct: 12313 rows, paper model -> -"), std::string::npos)
      << piped.err;
  EXPECT_FALSE(fs::exists(dir / "-"));
}

TEST(Pipes, CorrectPipedIntoFilterEqualsTheTwoCommandsOnFiles) {
  const auto dir = FreshDirectory("pipes_chain");
  const std::string corrected = (dir / "corrected.csv").string();
  const std::string filtered = (dir / "filtered.csv").string();
  ASSERT_EQ(RunCommand(Correct(kPush, corrected), dir).exit_code, 0);
  ASSERT_EQ(RunCommand(Filter(corrected, filtered), dir).exit_code, 0);
  const auto piped =
      RunCommand("cat " + kPush + " | " + Correct("-", "-") + " | " + Filter("-", "-"), dir);
  ASSERT_EQ(piped.exit_code, 0) << piped.err;
  EXPECT_TRUE(piped.out == ReadText(filtered)) << piped.out.substr(0, 400);
  EXPECT_NE(piped.err.find("pliant filter: 12313 rows -> -"), std::string::npos) << piped.err;
}

TEST(Pipes, TheSmootherReadsStdinToo) {
  const auto dir = FreshDirectory("pipes_smooth");
  const std::string smoothed = (dir / "smoothed.csv").string();
  ASSERT_EQ(RunCommand(Filter(kPush, smoothed, "--smooth"), dir).exit_code, 0);
  const auto piped = RunCommand(Filter("- < " + kPush, "-", "--smooth"), dir);
  ASSERT_EQ(piped.exit_code, 0) << piped.err;
  EXPECT_TRUE(piped.out == ReadText(smoothed));
}

TEST(Pipes, BadInputOnStdinIsNamedStdinWithItsLine) {
  const auto dir = FreshDirectory("pipes_bad");
  const auto result =
      RunCommand("printf 't,q1,q2,q3,tau1,tau2\\n0,0.1,0.2,0.15,0.3,x\\n' | " +
                     Correct("-", (dir / "out.csv").string()),
                 dir);
  EXPECT_EQ(result.exit_code, 2);
  EXPECT_EQ(result.err.rfind("<stdin>:2:", 0), 0u) << result.err;
  EXPECT_FALSE(fs::exists(dir / "out.csv"));
}

TEST(Pipes, DevNullAsTheOutputStaysTheDevice) {
  if (::geteuid() != 0) {
    GTEST_SKIP() << "only root could replace /dev/null, the damage this guards against";
  }
  const auto dir = FreshDirectory("pipes_devnull");
  const auto result = RunCommand(Correct(kPush, "/dev/null"), dir);
  EXPECT_EQ(result.exit_code, 0) << result.err;
  struct stat status {};
  ASSERT_EQ(::lstat("/dev/null", &status), 0);
  EXPECT_TRUE(S_ISCHR(status.st_mode));
}

}  // namespace
}  // namespace pliant
