// The real JHU 2017 files record one joint each, and each joint's depth range
// is identified from its own clamps: joint 1's run 0.0966–0.2265 m, joint 2's
// 0.0970–0.2269 m. A row of joint 1's log at 0.0966 m is inside joint 1's
// range; that it is outside joint 2's, which the log does not record, is no
// reason to warn (it did, on 127 and 119 rows of the logs the file was fitted on). Rows
// outside a recorded joint's range are still counted: Warning.FilterCountsRowsOutsideTheValidRange.
#include <gtest/gtest.h>

#include <string>

#include "run_command.h"

namespace pliant::testing {
namespace {

const std::string kCli = PLIANT_CLI;
const std::string kReal = std::string(PLIANT_SOURCE_DIR) + "/data/real/";

TEST(RealDepthRange, AJointTheLogDoesNotRecordHasNoRangeToLeave) {
  const auto dir = FreshDirectory("real_depth_range");
  const std::string logs = kReal + "jhu2017_bias_j1.csv " + kReal + "jhu2017_bias_j2.csv " +
                           kReal + "jhu2017_clamped_j1.csv " + kReal + "jhu2017_clamped_j2.csv";
  ASSERT_EQ(RunIn(dir, kCli + " identify " + logs + " -o real.json").exit_code, 0);
  const auto corrected =
      RunIn(dir, kCli + " correct --params real.json " + kReal + "jhu2017_clamped_j2.csv -o c.csv");
  ASSERT_EQ(corrected.exit_code, 0) << corrected.err;
  EXPECT_EQ(corrected.err.find("outside the parameters' valid range"), std::string::npos)
      << corrected.err;
  const auto filtered =
      RunIn(dir, kCli + " filter --params real.json " + kReal + "jhu2017_clamped_j1.csv -o f.csv");
  ASSERT_EQ(filtered.exit_code, 0) << filtered.err;
  EXPECT_NE(filtered.out.find("depth out of range 0,"), std::string::npos) << filtered.out;
}

}  // namespace
}  // namespace pliant::testing
