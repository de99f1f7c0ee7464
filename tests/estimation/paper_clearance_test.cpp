// The paper's procedure never writes a negative clearance: where a joint's
// loading and unloading lines cross, δ is written as 0 with a warning that
// says so. `pliant identify` refuses the case that produced it on the shipped
// data (a clamped beam without its bias sweep), so it is driven here through
// the library, which keeps the prior's bias table for such data.
#include <gtest/gtest.h>

#include <string>

#include "pliant/estimation/identification.h"
#include "pliant/io/log_reader.h"

namespace pliant::estimation {
namespace {

TEST(PaperProcedure, CrossingLinesGiveAZeroClearanceAndSaySo) {
  IdentificationData data;
  const std::string log = PLIANT_SOURCE_DIR "/data/clamped_beam.csv";
  AppendSamples(io::ReadLog(log), log, {}, &data);
  const IdentificationResult r = RunPaperProcedure(data, PaperPrior(), {});
  // Before the clamp: δ1 = −0.0024 rad (the lines' half gap).
  EXPECT_EQ(r.parameters.joints[0].backlash_rad, 0.0);
  EXPECT_GE(r.parameters.joints[1].backlash_rad, 0.0);
  std::string warnings;
  for (const auto& w : r.warnings) warnings += w + "\n";
  EXPECT_NE(warnings.find("joint 1: the loading and unloading lines cross (half their gap -0.00239"),
            std::string::npos)
      << warnings;
  EXPECT_NE(warnings.find("a clearance cannot be negative, so delta1 is written as 0"),
            std::string::npos)
      << warnings;
}

}  // namespace
}  // namespace pliant::estimation
