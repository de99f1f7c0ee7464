// The node's core without ROS transport: each measured_js of the real bag,
// filtered as it comes, gives what `pliant filter` gives on the bag's log.
#include "pliant/ros/joint_state_filter.h"

#include <gtest/gtest.h>

#include <cmath>
#include <string>

#include "pliant/estimation/filter_log.h"
#include "pliant/io/log_reader.h"
#include "pliant/io/log_writer.h"
#include "pliant/io/parameters_json.h"
#include "pliant/ros/crtk_bag.h"

namespace pliant::ros {
namespace {

const std::string kBag =
    PLIANT_SOURCE_DIR "/data/real/crtk-rosbag/pitch_exp_traj_01_test_cropped.bag";
const std::string kParams = PLIANT_SOURCE_DIR "/data/paper.json";

TEST(JointStateFilter, EveryMessageOfTheRealBagMatchesTheFilterOnItsLogToTheBit) {
  const io::Log log = ReadCrtkBag(kBag, {"PSM2"});
  const std::string in = ::testing::TempDir() + "/joint_state_filter_in.csv";
  const std::string out = ::testing::TempDir() + "/joint_state_filter_out.csv";
  io::WriteLog(in, log);
  const auto parameters = io::ReadParameters(kParams);
  estimation::FilterLog(in, out, parameters, {}, false, "", {});
  const io::Log filtered = io::ReadLog(out);
  const auto& h = filtered.header;
  const int t = h.Index("t"), q1 = h.Index("q1"), q2 = h.Index("q2"), q3 = h.Index("q3");
  const int tau1 = h.Index("tau1"), tau2 = h.Index("tau2"), v1 = h.Index("v1"), v2 = h.Index("v2");
  const int c1 = h.Index("q1_corr"), c2 = h.Index("q2_corr"), sd1 = h.Index("q1_sd");
  ASSERT_GT(filtered.Rows(), 3000u);
  JointStateFilter filter(parameters);
  const std::int64_t start_ns = 1'000'000'000'000;  // any origin: t is relative
  for (std::size_t r = 0; r < filtered.Rows(); ++r) {
    const double* row = &filtered.values[r * filtered.Columns()];
    JointStateIn message;
    message.stamp_ns = start_ns + std::llround(row[t] * 1e9);
    message.position = {row[q1], row[q2], row[q3], 0.1, 0.2, 0.3};
    message.effort = {row[tau1], row[tau2], 1.5, 0.0, 0.0, 0.0};
    message.velocity = {row[v1], row[v2], 0.0, 0.0, 0.0, 0.0};
    JointStateOut corrected;
    std::string why;
    ASSERT_TRUE(filter.Step(message, &corrected, &why)) << why;
    ASSERT_EQ(corrected.position.size(), 6u);
    EXPECT_EQ(corrected.position[0], row[c1]) << "row " << r;
    EXPECT_EQ(corrected.position[1], row[c2]) << "row " << r;
    EXPECT_EQ(corrected.position[2], row[q3]);
    EXPECT_EQ(corrected.position[5], 0.3);
    EXPECT_EQ(corrected.sd_rad[0], row[sd1]) << "row " << r;
  }
  EXPECT_EQ(filter.messages(), filtered.Rows());
}

TEST(JointStateFilter, SkipsShortMessagesAndStampsThatDoNotIncrease) {
  JointStateFilter filter(io::ReadParameters(kParams));
  JointStateOut out;
  std::string why;
  EXPECT_FALSE(filter.Step({10, {0.1, 0.2}, {0.0, 0.0}}, &out, &why));
  EXPECT_EQ(why, "a measured_js with 2 positions and 2 efforts (joints 1-3 need 3 and 2)");
  EXPECT_TRUE(filter.Step({10, {0.1, 0.2, 0.15}, {0.0, 0.0}}, &out, &why));
  EXPECT_FALSE(filter.Step({10, {0.1, 0.2, 0.15}, {0.0, 0.0}}, &out, &why));
  EXPECT_EQ(why, "a measured_js stamped 10 ns, not after the previous 10 ns");
  EXPECT_EQ(filter.messages(), 1u);
}

}  // namespace
}  // namespace pliant::ros
