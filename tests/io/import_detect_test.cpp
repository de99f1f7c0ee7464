// Recognising an import format from a file's content, on the shipped real files.
#include <gtest/gtest.h>

#include <string>

#include "pliant/io/import.h"
#include "pliant/io/input_error.h"
#include "temp_directory.h"

namespace pliant::io {
namespace {

using testing::TempDirectory;

const std::string kData = PLIANT_SOURCE_DIR "/data/";

std::string ErrorOf(const std::string& path) {
  try {
    DetectImportFormat(path);
  } catch (const InputError& e) {
    return e.what();
  }
  return "no error";
}

TEST(ImportDetect, EachShippedFileIsRecognised) {
  const auto clamped =
      DetectImportFormat(kData + "real/jhu-2017/hysteresis_output_joint_1_2017-7-25-19-46-31.csv");
  EXPECT_EQ(clamped.format, ImportFormat::kJhu2017ClampedBeam);
  EXPECT_EQ(clamped.evidence,
            "its header row: pos index, depth index, depth, current joint position, current joint "
            "effort, current torque offset");
  EXPECT_EQ(DetectImportFormat(
                kData + "real/jhu-2017/small_range_torque_offsets_joint_0_2017-7-26-16-43-2.csv")
                .format,
            ImportFormat::kJhu2017BiasSweep);
  const auto bag =
      DetectImportFormat(kData + "real/crtk-rosbag/pitch_exp_traj_01_test_cropped.bag");
  EXPECT_EQ(bag.format, ImportFormat::kRos1Bag);
  EXPECT_EQ(bag.evidence, "its first bytes, the ROS 1 bag magic '#ROSBAG V'");
  const auto ros2 = DetectImportFormat(kData + "examples/ros2-csv/PSM1-measured_js.csv");
  EXPECT_EQ(ros2.format, ImportFormat::kRos2Csv);
  EXPECT_EQ(ros2.evidence,
            "its header row: header.stamp.sec, header.stamp.nanosec, header.frame_id, name.0, "
            "name.1, name.2, ... 27 columns");
}

TEST(ImportDetect, AJhuFileMissingAColumnIsStillRecognised) {
  TempDirectory dir;
  // Without "current torque offset", so that the importer can name it.
  const std::string path = dir.Write(
      "a.csv", "pos index,depth index,depth,current joint position,current joint effort\n");
  EXPECT_EQ(DetectImportFormat(path).format, ImportFormat::kJhu2017ClampedBeam);
}

TEST(ImportDetect, ExtensionWhenTheContentSaysNothing) {
  TempDirectory dir;
  EXPECT_EQ(DetectImportFormat(dir.Write("cut.bag", "")).format, ImportFormat::kRos1Bag);
}

TEST(ImportDetect, UnknownFilesSayWhatToDo) {
  TempDirectory dir;
  const std::string other = dir.Write("other.csv", "\ntime,angle\n0,1\n");
  EXPECT_EQ(ErrorOf(other), other +
                                ":2: the header row (time, angle) matches none of the import "
                                "formats (jhu2017-clamped-beam, jhu2017-bias-sweep, ros1-bag, "
                                "ros2-csv) — name the format with --format NAME (docs/import.md "
                                "shows each), or convert the file to the canonical log "
                                "(docs/log-format.md)");
  const std::string log = dir.Write("log.csv", "# robot: PSM1\nt,q1,q2,q3,tau1,tau2\n");
  EXPECT_EQ(ErrorOf(log), log +
                              ":2: the file is already a canonical pliant log (t, q3, ...) — give "
                              "it to the other pliant commands directly; import reads other "
                              "formats");
  const std::string ros2_bag = dir.Write("run.db3", "SQLite format 3");
  EXPECT_EQ(ErrorOf(ros2_bag).rfind(ros2_bag + ": a ROS 2 bag is not read directly", 0), 0u);
  EXPECT_EQ(ErrorOf(dir.File("missing.csv")).rfind(dir.File("missing.csv") + ": cannot open", 0),
            0u);
}

TEST(ImportDetect, NamesRoundTrip) {
  for (auto format : {ImportFormat::kJhu2017ClampedBeam, ImportFormat::kJhu2017BiasSweep,
                      ImportFormat::kRos1Bag, ImportFormat::kRos2Csv}) {
    EXPECT_EQ(ParseImportFormat(ImportFormatName(format)), format);
  }
  EXPECT_FALSE(ParseImportFormat("csv").has_value());
}

}  // namespace
}  // namespace pliant::io
