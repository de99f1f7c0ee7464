// The ROS 2 extractor's CSVs, on the hand-written example in data/examples/ros2-csv
// (1 kHz measured_js with jitter, 500 Hz setpoint_js starting 0.4 ms earlier).
#include <gtest/gtest.h>

#include <cmath>
#include <string>
#include <utility>
#include <vector>

#include "pliant/io/import.h"
#include "pliant/io/input_error.h"
#include "pliant/io/log_reader.h"
#include "pliant/io/log_writer.h"
#include "temp_directory.h"

namespace pliant::io {
namespace {

using testing::TempDirectory;

const std::string kExample = PLIANT_SOURCE_DIR "/data/examples/ros2-csv/";
const std::string kMeasured = kExample + "PSM1-measured_js.csv";
const std::string kSetpoint = kExample + "PSM1-setpoint_js.csv";
const std::string kHeader =
    "header.stamp.sec,header.stamp.nanosec,position.0,position.1,position.2,effort.0,effort.1\n";

std::string ErrorOf(const std::vector<std::string>& paths, const ImportOptions& options = {}) {
  try {
    ImportRos2Csv(paths, options);
  } catch (const InputError& e) {
    return e.what();
  }
  return "no error";
}

TEST(ImportRos2Csv, MeasuredAndSetpointOfTheExample) {
  const Log log = ImportRos2Csv({kMeasured, kSetpoint}, {});
  ASSERT_EQ(log.Rows(), 10u);
  EXPECT_EQ(log.header.Metadata("arm"), "PSM1");
  EXPECT_EQ(log.header.Metadata("start_time").rfind("1718031600.120004117 s", 0), 0u);
  EXPECT_EQ(log.header.Metadata("joint_names").rfind("outer_yaw, outer_pitch, outer_insertion", 0),
            0u);
  const auto t = log.Column("t");
  EXPECT_DOUBLE_EQ(t[1], 0.001004);  // nanosec 121008117 - 120004117
  EXPECT_DOUBLE_EQ(t[9], 0.009003);  // 129007117 - 120004117
  EXPECT_EQ(log.Column("q1")[0], 0.0521);
  EXPECT_EQ(log.Column("q3")[0], 0.1489);
  EXPECT_EQ(log.Column("tau3")[0], 0.5738);
  EXPECT_EQ(log.Column("v1")[0], 0.28);
  // Setpoints at 119604117, 121604117, 123604117 ns: rows at 120004117 and
  // 121008117 hold the first, the row at 122012117 the second.
  const auto q1_cmd = log.Column("q1_cmd");
  EXPECT_EQ(q1_cmd[0], 0.0692);
  EXPECT_EQ(q1_cmd[1], 0.0692);
  EXPECT_EQ(q1_cmd[2], 0.06976);
  EXPECT_EQ(log.Column("q3_cmd")[2], 0.149242);
}

TEST(ImportRos2Csv, MeasuredAloneHasNoCommandAndReadsBack) {
  TempDirectory dir;
  const Log log = ImportRos2Csv({kMeasured}, {});
  EXPECT_FALSE(log.header.Has("q1_cmd"));
  WriteLog(dir.File("out.csv"), log);
  const Log back = ReadLog(dir.File("out.csv"));
  EXPECT_EQ(back.Rows(), 10u);
  EXPECT_TRUE(back.header.JointRecorded(1) && back.header.JointRecorded(2));
  EXPECT_FALSE(back.header.QuasiStatic());
}

TEST(ImportRos2Csv, TopicFromTheOptionAndMissingVelocityIsEmpty) {
  TempDirectory dir;
  const std::string path = dir.Write(
      "arm.csv", kHeader + "10,5,0.1,0.2,0.12,0.3,0.4\n10,1000005,0.1,0.2,0.12,0.3,0.4\n");
  EXPECT_EQ(ErrorOf({path}), path +
                                 ": the file name says neither measured_js nor setpoint_js — pass "
                                 "--topic measured_js (or setpoint_js), or keep the extractor's "
                                 "file name");
  const Log log = ImportRos2Csv({path}, {0, "measured_js"});
  EXPECT_DOUBLE_EQ(log.Column("t")[1], 0.001);
  EXPECT_TRUE(std::isnan(log.Column("v1")[0]) && std::isnan(log.Column("tau3")[1]));
}

TEST(ImportRos2Csv, BadFilesAreNamedAtTheirLine) {
  TempDirectory dir;
  const std::vector<std::pair<std::string, std::string>> cases = {
      {kHeader + "10,5,0.1,0.2,0.12,0.3,0.4\n10,4,0.1,0.2,0.12,0.3,0.4\n",
       ":3:1: header.stamp is not after the previous row's — the rows must be in time order, one "
       "per message: sort them by stamp and remove repeated messages"},
      {kHeader + "10,5,0.1,0.2,0.12,0.3,x\n",
       ":2:7: value 'x' in column 'effort.1' is not a finite number — the importer reads plain "
       "decimal numbers such as 0.25 or -1e-3: repair the cell, or check that the file is the "
       "format named on stderr"},
      {kHeader + "10,2e9,0.1,0.2,0.12,0.3,0.4\n",
       ":2:1: header.stamp 10 s + 2e+09 ns is not a ROS time stamp — sec and nanosec are "
       "whole numbers, sec within 32 bits, nanosec below 1e9"},
      {"header.stamp.sec,header.stamp.nanosec,position.0,position.1,position.2\n10,5,0,0,0.1\n",
       ":1: missing column 'effort.0' of the ros2-csv format; columns found: header.stamp.sec, "
       "header.stamp.nanosec, position.0, position.1, position.2 — give the file as the "
       "recording wrote it, or choose the right format with --format (pliant import --help lists "
       "them)"},
      {kHeader + "10,5,0.1,0.2,120,0.3,0.4\n",
       ":2:5: 'position.2' = 120 is outside 0 to 0.3 — position.2 is the PSM insertion depth in "
       "metres: import a PSM's topic"},
      {kHeader + "0,0,0.1,0.2,0.12,0.3,0.4\n100000000,0,0.1,0.2,0.12,0.3,0.4\n"
                 "100000000,1,0.1,0.2,0.12,0.3,0.4\n",
       ":4:1: header.stamp is 1e+08 s after the first row's, too far for its nanoseconds to "
       "count — one recording spans hours, not months: split the file where its stamps jump, or "
       "remove the stray row"},
  };
  for (const auto& [text, message] : cases) {
    const std::string path = dir.Write("measured_js.csv", text);
    EXPECT_EQ(ErrorOf({path}), path + message);
  }
}

// ROS 2's sec is an int32: a clock never set stamps before 1970, and t still counts from it.
TEST(ImportRos2Csv, AStampBefore1970StartsTheLogAtItsExactTime) {
  TempDirectory dir;
  const std::string path = dir.Write("measured_js.csv",
                                     kHeader +
                                         "-718031600,120004117,0.1,0.2,0.12,0.3,0.4\n"
                                         "-718031600,121004117,0.1,0.2,0.12,0.3,0.4\n");
  const Log log = ImportRos2Csv({path}, {});
  EXPECT_EQ(log.header.Metadata("start_time").rfind("-718031599.879995883 s", 0), 0u);
  EXPECT_DOUBLE_EQ(log.Column("t")[1], 0.001);
}

TEST(ImportRos2Csv, TwoMeasuredFilesAreRefused) {
  EXPECT_EQ(ErrorOf({kMeasured, kMeasured}),
            kMeasured +
                ": ros2-csv takes one measured_js file and at most one setpoint_js file; got 2 "
                "and 0 — import one arm's measured_js.csv, with its setpoint_js.csv if you have "
                "it");
}

}  // namespace
}  // namespace pliant::io
