#include "pliant/ros/crtk_bag.h"

#include <gtest/gtest.h>
#include <rosbag/bag.h>
#include <sensor_msgs/JointState.h>

#include <cmath>
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <string>
#include <vector>

#include "pliant/io/input_error.h"

namespace pliant::ros {
namespace {

const std::string kRealBag =
    PLIANT_SOURCE_DIR "/data/real/crtk-rosbag/pitch_exp_traj_01_test_cropped.bag";

class ScratchDirectory {
 public:
  ScratchDirectory() {
    const auto* info = ::testing::UnitTest::GetInstance()->current_test_info();
    path_ =
        std::filesystem::path(::testing::TempDir()) / ("pliant_ros_" + std::string(info->name()));
    std::filesystem::remove_all(path_);
    std::filesystem::create_directories(path_);
  }
  ~ScratchDirectory() { std::filesystem::remove_all(path_); }
  std::string File(const std::string& name) const { return (path_ / name).string(); }

 private:
  std::filesystem::path path_;
};

sensor_msgs::JointState JointState(double stamp_s, int joints);

struct Record {
  std::string topic;
  double stamp_s;  ///< header.stamp after 1700000000 s
  int joints;
};

// A bag of JointState messages, received one second apart in the order given.
std::string WriteBag(const ScratchDirectory& scratch, const std::string& name,
                     const std::vector<Record>& records) {
  const std::string path = scratch.File(name);
  rosbag::Bag bag(path, rosbag::bagmode::Write);
  for (std::size_t i = 0; i < records.size(); ++i) {
    bag.write(records[i].topic, ::ros::Time(1700000000.0 + static_cast<double>(i)),
              JointState(records[i].stamp_s, records[i].joints));
  }
  return path;
}

std::string InputErrorOf(const std::string& path, const std::string& arm) {
  try {
    ReadCrtkBag(path, {arm});
  } catch (const io::InputError& e) {
    return e.what();
  }
  return "no error";
}

sensor_msgs::JointState JointState(double stamp_s, int joints) {
  sensor_msgs::JointState message;
  message.header.stamp =
      ::ros::Time(1700000000, static_cast<std::uint32_t>(std::lround(stamp_s * 1e9)));
  for (int i = 0; i < joints; ++i) {
    message.position.push_back(0.1 * (i + 1) + stamp_s);
    message.effort.push_back(-0.2 * (i + 1));
  }
  return message;
}

// The shared bag, checked against rosbag's Python reader on the same file:
// 3420 messages on /PSM2/measured_js, the first stamped 1644257420.444057563,
// the first /PSM2/setpoint_js 489 ns later.
TEST(CrtkBag, ReadsTheRealPsm2Bag) {
  const io::Log log = ReadCrtkBag(kRealBag, {});
  ASSERT_EQ(log.Rows(), 3420u);
  EXPECT_EQ(log.header.Metadata("arm"), "PSM2");
  EXPECT_EQ(log.header.Metadata("format"), "ros1-bag");
  EXPECT_EQ(log.header.Metadata("start_time").rfind("1644257420.444057563 s", 0), 0u);
  const auto t = log.Column("t");
  EXPECT_EQ(t[0], 0.0);
  EXPECT_DOUBLE_EQ(t[1], 0.010136129);
  EXPECT_DOUBLE_EQ(t.back(), 34.418187061);
  EXPECT_DOUBLE_EQ(log.Column("q1")[0], 0.05215933783251234);
  EXPECT_DOUBLE_EQ(log.Column("q2")[0], 0.009676584291403311);
  EXPECT_DOUBLE_EQ(log.Column("q3")[0], 0.14890223972000002);
  EXPECT_DOUBLE_EQ(log.Column("tau1")[0], 0.9264845813669761);
  EXPECT_DOUBLE_EQ(log.Column("tau2")[0], -0.23487958345810117);
  EXPECT_DOUBLE_EQ(log.Column("tau3")[0], 0.5737794716046472);
  // The first setpoint is stamped after the first measurement: nothing to hold yet.
  EXPECT_TRUE(std::isnan(log.Column("q1_cmd")[0]));
  EXPECT_DOUBLE_EQ(log.Column("q1_cmd")[1], 0.06922823227718565);
  EXPECT_DOUBLE_EQ(log.Column("q3_cmd")[1], 0.14923382763924098);
}

TEST(CrtkBag, NamedArmGivesTheSameLog) {
  EXPECT_EQ(ReadCrtkBag(kRealBag, {"PSM2"}).values.size(), ReadCrtkBag(kRealBag, {}).values.size());
}

TEST(CrtkBag, WrongArmListsTheArmsFound) {
  EXPECT_EQ(InputErrorOf(kRealBag, "PSM1"),
            kRealBag +
                ": the bag has no /PSM1/measured_js; arms found: PSM2 — pass one of them with "
                "--arm NAME (names are case-sensitive)");
}

TEST(CrtkBag, TruncatedBagIsAnInputError) {
  ScratchDirectory scratch;
  const std::string cut = scratch.File("cut.bag");
  std::ifstream in(kRealBag, std::ios::binary);
  std::string bytes(std::istreambuf_iterator<char>(in), {});
  std::ofstream(cut, std::ios::binary) << bytes.substr(0, bytes.size() / 2);
  const std::string message = InputErrorOf(cut, "");
  EXPECT_EQ(message.rfind(cut + ": not a readable ROS 1 bag (rosbag: ", 0), 0u) << message;
  EXPECT_NE(message.find("rosbag reindex"), std::string::npos) << message;
}

TEST(CrtkBag, TextFileIsNotABag) {
  ScratchDirectory scratch;
  const std::string text = scratch.File("log.bag");
  std::ofstream(text) << "t,q1\n0,1\n";
  EXPECT_EQ(InputErrorOf(text, "").rfind(text + ": not a readable ROS 1 bag", 0), 0u);
}

// The message a one-message bag is refused with, after "PATH".
std::string RefusalOfOneMessage(const Record& record) {
  ScratchDirectory scratch;
  const std::string path = WriteBag(scratch, "one.bag", {record});
  const std::string message = InputErrorOf(path, "");
  return message.rfind(path, 0) == 0 ? message.substr(path.size()) : message;
}

TEST(CrtkBag, BagWithoutMeasuredJsNamesItsTopics) {
  EXPECT_EQ(RefusalOfOneMessage({"/PSM1/setpoint_js", 0.0, 6}),
            ": the bag has no sensor_msgs/JointState topic /ARM/measured_js; topics found: "
            "/PSM1/setpoint_js — record the arm's CRTK joint state (rosbag record "
            "/PSM1/measured_js /PSM1/setpoint_js), dVRK 2.x publishes it for every arm");
}

TEST(CrtkBag, SeveralArmsNeedAName) {
  ScratchDirectory scratch;
  std::vector<Record> records;
  for (int i = 0; i < 3; ++i) {
    records.push_back({"/PSM1/measured_js", 0.01 * i, 6});
    records.push_back({"/PSM3/measured_js", 0.01 * i, 6});
  }
  const std::string path = WriteBag(scratch, "two_arms.bag", records);
  EXPECT_EQ(
      InputErrorOf(path, ""),
      path + ": the bag has measured_js for several arms: PSM1, PSM3 — choose one with --arm NAME");
  const io::Log log = ReadCrtkBag(path, {"PSM3"});
  ASSERT_EQ(log.Rows(), 3u);
  EXPECT_DOUBLE_EQ(log.Column("t")[2], 0.02);
  EXPECT_DOUBLE_EQ(log.Column("q2")[2], 0.22);
  EXPECT_FALSE(log.header.Has("q1_cmd"));  // no setpoint_js in this bag
}

TEST(CrtkBag, SetpointIsTheLatestAtOrBeforeEachMeasurement) {
  ScratchDirectory scratch;
  // Measurements every 10 ms, setpoints stamped at 5 ms and at exactly 20 ms.
  const std::string path = WriteBag(scratch, "setpoints.bag",
                                    {{"/PSM1/setpoint_js", 0.005, 3},
                                     {"/PSM1/measured_js", 0.0, 3},
                                     {"/PSM1/measured_js", 0.01, 3},
                                     {"/PSM1/setpoint_js", 0.02, 3},
                                     {"/PSM1/measured_js", 0.02, 3},
                                     {"/PSM1/measured_js", 0.03, 3}});
  const auto q1_cmd = ReadCrtkBag(path, {}).Column("q1_cmd");
  ASSERT_EQ(q1_cmd.size(), 4u);
  EXPECT_TRUE(std::isnan(q1_cmd[0]));        // t = 0: before the first setpoint
  EXPECT_DOUBLE_EQ(q1_cmd[1], 0.1 + 0.005);  // t = 0.01: the setpoint of 0.005
  EXPECT_DOUBLE_EQ(q1_cmd[2], 0.1 + 0.02);   // t = 0.02: the one stamped at the same time
  EXPECT_DOUBLE_EQ(q1_cmd[3], 0.1 + 0.02);
}

TEST(CrtkBag, TooFewJointsIsAnInputError) {
  EXPECT_EQ(RefusalOfOneMessage({"/ECM/measured_js", 0.0, 2}),
            ": message 1 on /ECM/measured_js has 2 position entries, fewer than 3 — joints 1-3 "
            "need position[0..2] and effort[0..1]: record the arm's own measured_js, not a "
            "reduced joint state");
}

}  // namespace
}  // namespace pliant::ros
