// The JHU 2017 importers on the shipped real files (data/real/jhu-2017), and on
// broken copies of them.
#include <gtest/gtest.h>

#include <cmath>
#include <set>
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

using testing::ReadText;
using testing::TempDirectory;

const std::string kJhu = PLIANT_SOURCE_DIR "/data/real/jhu-2017/";
const std::string kClamped1 = kJhu + "hysteresis_output_joint_0_2017-7-25-20-30-58.csv";
const std::string kClamped2 = kJhu + "hysteresis_output_joint_1_2017-7-25-19-46-31.csv";
const std::string kBias1 = kJhu + "small_range_torque_offsets_joint_0_2017-7-26-16-43-2.csv";
const std::string kBias2 = kJhu + "small_range_torque_offsets_joint_1_2017-7-26-19-22-11.csv";
const std::string kClampedHeader =
    "pos index,depth index,depth,current joint position,current joint effort,current torque "
    "offset\n";

std::size_t DistinctValues(const std::vector<double>& column) {
  return std::set<double>(column.begin(), column.end()).size();
}

// The message of the InputError that importing `text` (as a joint-0 clamped-beam
// file) raises, with the file's path cut off.
std::string ClampedError(const std::string& text) {
  TempDirectory dir;
  const std::string path = dir.Write("hysteresis_output_joint_0_x.csv", text);
  try {
    ImportJhu2017ClampedBeam(path, {});
  } catch (const InputError& e) {
    return std::string(e.what()).substr(path.size());
  }
  return "no error";
}

TEST(ImportJhu2017, ClampedBeamJointOneHasEveryRowAndNoJointTwo) {
  const Log log = ImportJhu2017ClampedBeam(kClamped1, {});
  ASSERT_EQ(log.Rows(), 1906u);  // the file's 1907 lines less its header
  EXPECT_EQ(log.header.columns, (std::vector<std::string>{"t", "q1", "q3", "tau1", "tip_fixed",
                                                          "segment", "tau1_bias", "pose_index"}));
  EXPECT_EQ(log.header.Metadata("timing"), "quasi-static");
  EXPECT_EQ(log.header.Metadata("joint_recorded"), "1");
  EXPECT_EQ(log.header.Metadata("recorded").substr(0, 19), "2017-07-25 20:30:58");
  // First data line: 0,0,0.0966426324,-0.002212563,0.2245435265,0.0892154562
  const std::vector<double> first(log.values.begin(), log.values.begin() + 8);
  EXPECT_EQ(first, (std::vector<double>{0, -0.002212563, 0.0966426324, 0.2245435265, 1, 0,
                                        0.0892154562, 0}));
  EXPECT_EQ(DistinctValues(log.Column("segment")), 14u);
  EXPECT_EQ(log.Column("t").back(), 1905.0);
  EXPECT_EQ(log.Column("pose_index").back(), -9.0);  // last line: -9,13,0.2264078725,...
}

TEST(ImportJhu2017, ClampedBeamJointTwoFromTheFileName) {
  const Log log = ImportJhu2017ClampedBeam(kClamped2, {});
  ASSERT_EQ(log.Rows(), 1294u);
  EXPECT_TRUE(log.header.Has("q2") && log.header.Has("tau2") && log.header.Has("tau2_bias"));
  EXPECT_FALSE(log.header.Has("q1") || log.header.Has("tau1"));
  EXPECT_EQ(log.Column("q2")[0], 6.56432294309083E-06);
  EXPECT_EQ(DistinctValues(log.Column("segment")), 14u);
}

TEST(ImportJhu2017, WrittenLogReadsBackAsOneJointQuasiStatic) {
  TempDirectory dir;
  const std::string path = dir.File("clamped_j2.csv");
  WriteLog(path, ImportJhu2017ClampedBeam(kClamped2, {}));
  const std::string text = ReadText(path);
  EXPECT_NE(text.find("\n# timing: quasi-static\n"), std::string::npos);
  EXPECT_NE(text.find("\nt,q2,q3,tau2,tip_fixed,segment,tau2_bias,pose_index\n"
                      "0,6.56432294309083e-06,0.0970467509,-0.0018254573,1,0,-0.0882050766,0\n"),
            std::string::npos);
  const Log back = ReadLog(path);
  EXPECT_EQ(back.Rows(), 1294u);
  EXPECT_TRUE(back.header.QuasiStatic());
  EXPECT_TRUE(back.header.JointRecorded(2));
  EXPECT_FALSE(back.header.JointRecorded(1));
  EXPECT_TRUE(std::isnan(back.Column("q1")[0]) && std::isnan(back.Column("tau1")[1293]));
  EXPECT_EQ(back.Column("tau2_bias")[1293], -0.2104109971);
}

TEST(ImportJhu2017, BiasSweepRelabelsRowsTakenBeforeTheDepthMoveAndDropsTheStartPose) {
  const Log log = ImportJhu2017BiasSweep(kBias1, {});
  ASSERT_EQ(log.Rows(), 1203u);  // 1204 rows less the start pose (line 2, depth 0.1599 m)
  EXPECT_EQ(log.header.Metadata("dropped").rfind("line 2 (depth index 0): depth 0.1598973715", 0),
            0u);
  EXPECT_EQ(log.header.Metadata("relabelled").rfind("13 rows (lines 88, 174, 260,", 0), 0u);
  const auto segment = log.Column("segment");
  const auto in_file = log.Column("depth_index_in_file");
  const auto depth = log.Column("q3");
  EXPECT_EQ(DistinctValues(segment), 14u);
  // Line 88 (row 85 after the drop): file index 1, measured at depth 0 (0.0900 m).
  EXPECT_EQ(in_file[85], 1.0);
  EXPECT_EQ(segment[85], 0.0);
  EXPECT_NEAR(depth[85], 0.090010488729999977, 1e-15);
  EXPECT_EQ(segment[86], 1.0);
  // Within each segment the depth now holds still to 0.1 mm.
  for (std::size_t r = 1; r < log.Rows(); ++r) {
    if (segment[r] == segment[r - 1]) ASSERT_NEAR(depth[r], depth[r - 1], 1e-4) << "row " << r;
  }
  EXPECT_EQ(log.Column("tip_fixed")[0], 0.0);
  EXPECT_EQ(log.Column("q1")[0], -0.0027925268031909274);
  EXPECT_EQ(log.Column("tau1")[0], 0.092047574915427338);
}

TEST(ImportJhu2017, BiasSweepJointTwo) {
  const Log log = ImportJhu2017BiasSweep(kBias2, {});
  EXPECT_EQ(log.Rows(), 2239u);
  EXPECT_TRUE(log.header.Has("q2") && !log.header.Has("q1"));
  EXPECT_EQ(DistinctValues(log.Column("segment")), 14u);
}

TEST(ImportJhu2017, JointFromTheOptionWhenTheNameDoesNotTell) {
  TempDirectory dir;
  const std::string path = dir.Write("renamed.csv", kClampedHeader + "0,0,0.1,0.01,0.2,0.1\n");
  EXPECT_THROW(ImportJhu2017ClampedBeam(path, {}), InputError);
  EXPECT_TRUE(ImportJhu2017ClampedBeam(path, {2, ""}).header.Has("q2"));
}

TEST(ImportJhu2017, MissingColumnNamesItAndTheColumnsFound) {
  EXPECT_EQ(ClampedError("pos index,depth index,depth,current joint position,current joint "
                         "effort\n0,0,0.1,0.01,0.2\n"),
            ":1: missing column 'current torque offset' of the jhu2017-clamped-beam format; "
            "columns found: pos index, depth index, depth, current joint position, current joint "
            "effort — give the file as the recording wrote it, or choose the right format with "
            "--format (pliant import --help lists them)");
}

// data/real's logs are what the importer writes today, and the log reader takes
// them as one joint, quasi-static.
TEST(ImportJhu2017, ShippedLogsAreTheImportersOutput) {
  TempDirectory dir;
  const std::vector<std::pair<std::string, std::string>> shipped = {
      {kClamped1, "jhu2017_clamped_j1.csv"},
      {kClamped2, "jhu2017_clamped_j2.csv"},
      {kBias1, "jhu2017_bias_j1.csv"},
      {kBias2, "jhu2017_bias_j2.csv"}};
  for (const auto& [source, name] : shipped) {
    const bool clamped = name.find("clamped") != std::string::npos;
    WriteLog(dir.File(name),
             clamped ? ImportJhu2017ClampedBeam(source, {}) : ImportJhu2017BiasSweep(source, {}));
    const std::string path = PLIANT_SOURCE_DIR "/data/real/" + name;
    EXPECT_EQ(ReadText(path), ReadText(dir.File(name)))
        << name << ": regenerate (data/real/README.md)";
    const Log log = ReadLog(path);
    const int joint = name[name.size() - 5] - '0';  // "..._jN.csv"
    EXPECT_TRUE(log.header.QuasiStatic()) << name;
    EXPECT_TRUE(log.header.JointRecorded(joint)) << name;
    EXPECT_FALSE(log.header.JointRecorded(3 - joint)) << name;
  }
}

// Each broken cell or row, named at its line (and column) with its fix.
TEST(ImportJhu2017, BadRowsAreNamedAtTheirLineAndColumn) {
  const std::string good = kClampedHeader + "0,0,0.1,0.01,0.2,0.1\n";
  const std::vector<std::pair<std::string, std::string>> cases = {
      {good + "1,0,0.1,abc,0.2,0.1\n",
       ":3:4: value 'abc' in column 'current joint position' is not a finite number — the "
       "importer reads plain decimal numbers such as 0.25 or -1e-3: repair the cell, or check "
       "that the file is the format named on stderr"},
      {good + "1,0,0.1",
       ":3: row has 3 fields but the header has 6 columns — every row needs one value per header "
       "column; look for a missing or extra comma, or a row cut short"},
      {kClampedHeader + "0,0,96.6,0.01,0.2,0.1\n",
       ":2:3: 'depth' = 96.6 is outside 0 to 0.3 — the insertion depth is in metres, 0 to 0.3 m: "
       "check the column and its units"},
      {kClampedHeader + "0,0,0.1,,0.2,0.1\n",
       ":2:4: column 'current joint position' holds no value — every row needs a number in this "
       "column: repair or remove the row"},
      {kClampedHeader + "0,0.5,0.1,0.01,0.2,0.1\n",
       ":2:2: depth index 0.5 is not a whole number >= 0 — the depth index counts the insertion "
       "depths from 0: repair the cell"},
      {kClampedHeader + "0,0,0.1,0.01,inf,0.1\n",
       ":2:5: column 'current joint effort' holds 'inf' — write finite values; leave the field "
       "empty when the value is missing"},
  };
  for (const auto& [text, message] : cases) EXPECT_EQ(ClampedError(text), message) << text;
}

}  // namespace
}  // namespace pliant::io
