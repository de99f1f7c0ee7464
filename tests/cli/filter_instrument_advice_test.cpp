// pliant filter says when the instrument's constant states end far beyond
// the σ the parameters file gives them (filter_log.cpp, InstrumentAdvice):
// on the real JHU 2017 clamps (data/real/README.md) with the paper's
// parameters, another arm's, the clearance ends 8 σ from the file's δ; with
// the parameters identified on those logs nothing is said.
#include <gtest/gtest.h>

#include <string>

#include "run_command.h"

namespace pliant::testing {
namespace {

const std::string kCli = PLIANT_CLI;
const std::string kSource = PLIANT_SOURCE_DIR;
const std::string kReal = kSource + "/data/real/";
const std::string kAdvice = "joint 1's clearance ended";

TEST(FilterInstrumentAdvice, AnotherArmsClearanceIsSaidNotToFitTheRealClamps) {
  const auto dir = FreshDirectory("filter_instrument_advice");
  // Measured: −8.47 mrad from the paper's δ, 8 σ of the default 1 mrad.
  const auto paper = RunIn(dir, kCli + " filter --params " + kSource + "/data/paper.json " +
                                    kReal + "jhu2017_clamped_j1.csv -o paper.csv");
  ASSERT_EQ(paper.exit_code, 0) << paper.err;
  const std::string said = paper.out + paper.err;
  EXPECT_NE(said.find(kAdvice), std::string::npos) << said;
  EXPECT_NE(said.find("identify on this instrument"), std::string::npos) << said;

  const auto identified = RunIn(dir, kCli + " identify --quiet " + kReal + "jhu2017_bias_j1.csv " +
                                         kReal + "jhu2017_clamped_j1.csv -o j1.json");
  ASSERT_EQ(identified.exit_code, 0) << identified.err;
  const auto own = RunIn(dir, kCli + " filter --params j1.json " + kReal +
                                  "jhu2017_clamped_j1.csv -o own.csv");
  ASSERT_EQ(own.exit_code, 0) << own.err;
  EXPECT_EQ((own.out + own.err).find("ended"), std::string::npos) << own.out + own.err;
}

// The smoothed pass says the same (its forward filter's states).
TEST(FilterInstrumentAdvice, TheSmoothedPassSaysItToo) {
  const auto dir = FreshDirectory("filter_instrument_advice_smooth");
  const auto run = RunIn(dir, kCli + " filter --smooth --params " + kSource + "/data/paper.json " +
                                  kReal + "jhu2017_clamped_j1.csv -o smoothed.csv");
  ASSERT_EQ(run.exit_code, 0) << run.err;
  EXPECT_NE((run.out + run.err).find(kAdvice), std::string::npos) << run.out + run.err;
}

}  // namespace
}  // namespace pliant::testing
