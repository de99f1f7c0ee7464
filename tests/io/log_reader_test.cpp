#include "pliant/io/log_reader.h"

#include <gtest/gtest.h>

#include <cmath>
#include <string>

#include "temp_directory.h"

namespace pliant::io {
namespace {

using testing::TempDirectory;

const std::string kHeader = "t,q1,q2,q3,tau1,tau2\n";
const std::string kRequiredFix =
    " \u2014 give every row a finite t, q1, q2, q3, tau1 and tau2, or pass --skip-bad-rows "
    "(option skip_bad_rows) to drop and count such rows";

class LogReaderTest : public ::testing::Test {
 protected:
  // The message of the InputError reading `contents` throws, with the path
  // replaced by FILE; "no error" when it reads.
  std::string ErrorOf(const std::string& contents, LogReaderOptions options = {}) {
    const std::string path = directory_.Write("log.csv", contents);
    try {
      ReadLog(path, options);
    } catch (const InputError& error) {
      std::string text = error.what();
      EXPECT_EQ(text.rfind(path, 0), 0u) << text;
      EXPECT_EQ(error.file(), path);
      return "FILE" + text.substr(path.size());
    }
    return "no error";
  }
  Log Read(const std::string& contents, LogReaderOptions options = {}) {
    return ReadLog(directory_.Write("log.csv", contents), options);
  }

  TempDirectory directory_;
};

TEST_F(LogReaderTest, ReadsRequiredColumns) {
  const Log log = Read(kHeader + "0,0.1,-0.2,0.15,0.5,-0.25\n0.001,0.2,-0.3,0.16,1.5,2\n");
  ASSERT_EQ(log.Rows(), 2u);
  ASSERT_EQ(log.Columns(), 6u);
  EXPECT_EQ(log.Value(0, 1), 0.1);
  EXPECT_EQ(log.Value(0, 5), -0.25);
  EXPECT_EQ(log.Value(1, 0), 0.001);
  EXPECT_EQ(log.Column("q3"), (std::vector<double>{0.15, 0.16}));
  EXPECT_THROW(log.Column("v1"), std::out_of_range);
}

TEST_F(LogReaderTest, AcceptsAnyColumnOrderAndKeepsAuxiliaryColumns) {
  const Log log = Read("tau2,motor_temp,q3,t,v1,q2,tau1,q1\n-1,41.5,0.1,2,,0.3,1,-0.4\n");
  const StandardColumns columns(log.header);
  EXPECT_EQ(columns.t, 3);
  EXPECT_EQ(columns.q1, 7);
  EXPECT_EQ(columns.tau2, 0);
  EXPECT_EQ(columns.v1, 4);
  EXPECT_EQ(columns.q1_ref, -1);
  EXPECT_EQ(log.Value(0, columns.q1), -0.4);
  EXPECT_EQ(log.Value(0, columns.tau2), -1.0);
  EXPECT_EQ(log.Value(0, log.header.Index("motor_temp")), 41.5);
  EXPECT_TRUE(std::isnan(log.Value(0, columns.v1)));  // empty optional field: missing
}

TEST_F(LogReaderTest, KeepsMetadataInOrderAndCountsItsLines) {
  const std::string text =
      "# robot: PSM1\n# note: clamp: rigid \n#flag\n" + kHeader + "0,0,0,0.1,0,0\n0,0,0,0.1,0,0\n";
  EXPECT_EQ(ErrorOf(text),
            "FILE:6:1: t = 0 s is not greater than the previous row's t = 0 s \u2014 t must be "
            "strictly increasing: sort the rows by time and remove repeated samples");
  LogReader reader(directory_.Write(
      "m.csv", "# robot: PSM1\n# note: clamp: rigid \n#flag\n" + kHeader + "0,0,0,0.1,0,0\n"));
  using Entry = std::pair<std::string, std::string>;
  EXPECT_EQ(reader.header().metadata,
            (std::vector<Entry>{{"robot", "PSM1"}, {"note", "clamp: rigid"}, {"flag", ""}}));
  EXPECT_EQ(reader.header().Metadata("note"), "clamp: rigid");
  EXPECT_EQ(reader.header().Metadata("absent"), "");
  ASSERT_NE(reader.Next(), nullptr);
  EXPECT_EQ(reader.line(), 5u);
}

TEST_F(LogReaderTest, AcceptsCrlfBomBlankLinesAndNoFinalNewline) {
  const Log log = Read(
      "\xEF\xBB\xBF# source: ros2\r\nt,q1,q2,q3,tau1,tau2\r\n0,1,2,0.1,3,4\r\n\r\n"
      "1, +1.5 ,2,0.1,3,4");
  ASSERT_EQ(log.Rows(), 2u);
  EXPECT_EQ(log.header.metadata[0].first, "source");
  EXPECT_EQ(log.header.metadata[0].second, "ros2");
  EXPECT_EQ(log.header.columns.front(), "t");
  EXPECT_EQ(log.header.columns.back(), "tau2");
  EXPECT_EQ(log.Value(1, 1), 1.5);
  EXPECT_EQ(log.Value(1, 5), 4.0);
  const Log bom_header = Read("\xEF\xBB\xBFt,q1,q2,q3,tau1,tau2\n0,1,2,0.1,3,4\n");
  EXPECT_EQ(bom_header.header.Index("t"), 0);
}

TEST_F(LogReaderTest, StreamsRowsAndStopsAtTheEnd) {
  LogReader reader(directory_.Write("s.csv", kHeader + "0,1,2,0.1,3,4\n\n1,1,2,0.1,3,4\n"));
  ASSERT_NE(reader.Next(), nullptr);
  EXPECT_EQ(reader.line(), 2u);
  const double* row = reader.Next();
  ASSERT_NE(row, nullptr);
  EXPECT_EQ(row[0], 1.0);
  EXPECT_EQ(reader.line(), 4u);
  EXPECT_EQ(reader.Next(), nullptr);
  EXPECT_EQ(reader.Next(), nullptr);
  EXPECT_EQ(reader.rows(), 2u);
}

TEST_F(LogReaderTest, MissingFile) {
  const std::string path = directory_.File("absent.csv");
  try {
    LogReader reader(path);
    FAIL() << "opened a missing file";
  } catch (const InputError& error) {
    EXPECT_EQ(std::string(error.what()),
              path +
                  ": cannot open the log (No such file or directory) \u2014 check the path and "
                  "that the file is readable");
    EXPECT_EQ(error.line(), 0u);
  }
}

TEST_F(LogReaderTest, EmptyFileAndNoHeader) {
  EXPECT_EQ(ErrorOf(""),
            "FILE: the file is empty \u2014 a log needs a header row (t,q1,q2,q3,tau1,tau2) and "
            "at least one data row");
  EXPECT_EQ(ErrorOf("# robot: PSM1\n"),
            "FILE:1: the file has metadata lines but no header row \u2014 add a header row naming "
            "the columns (t,q1,q2,q3,tau1,tau2 at least) after the metadata");
}

TEST_F(LogReaderTest, NoDataRows) {
  EXPECT_EQ(
      ErrorOf("# a: 1\n" + kHeader + "\n"),
      "FILE:2: the log has a header but no data rows \u2014 add data rows below the header row");
}

TEST_F(LogReaderTest, MissingRequiredColumnsAreNamedWithTheColumnsFound) {
  EXPECT_EQ(ErrorOf("t,q1,q2,tau1,tau2\n0,0,0,0,0\n"),
            "FILE:1: missing required column 'q3' (joint 3 insertion depth in m); columns found: "
            "t, q1, q2, tau1, tau2 \u2014 add the missing columns, or rename the columns that hold "
            "these quantities");
  EXPECT_EQ(ErrorOf("time,q1,q2,q3,effort1,tau2\n"),
            "FILE:1: missing required columns 't' (time in s), 'tau1' (joint 1 effort in N·m); "
            "columns found: time, q1, q2, q3, effort1, tau2 \u2014 add the missing columns, or "
            "rename the columns that hold these quantities");
}

TEST_F(LogReaderTest, DuplicateAndUnnamedColumns) {
  EXPECT_EQ(ErrorOf("t,q1,q2,q3,q1,tau1,tau2\n"),
            "FILE:1:5: duplicate column 'q1' (also column 2) \u2014 give every column a distinct "
            "name");
  EXPECT_EQ(ErrorOf(kHeader.substr(0, kHeader.size() - 1) + ",\n"),
            "FILE:1:7: column 7 of the header has no name \u2014 name every column, and remove any "
            "trailing comma from the header row");
}

TEST_F(LogReaderTest, WrongNumberOfFields) {
  const std::string fix =
      " \u2014 every row needs one value per header column; look for a missing or extra comma";
  EXPECT_EQ(ErrorOf(kHeader + "0,0,0,0.1,0,0\n1,0,0,0.1,0\n"),
            "FILE:3: row has 5 fields but the header has 6 columns" + fix);
  EXPECT_EQ(ErrorOf(kHeader + "0,0,0,0.1,0,0,7,8\n"),
            "FILE:2: row has 8 fields but the header has 6 columns" + fix);
}

TEST_F(LogReaderTest, NonNumericValueIsQuotedWithItsColumn) {
  const std::string fix =
      " \u2014 write plain decimal numbers such as 0.25 or -1e-3 (no units, quotes or thousands "
      "separators), and remove columns that hold text";
  EXPECT_EQ(ErrorOf(kHeader + "0,0,abc,0.1,0,0\n"),
            "FILE:2:3: value 'abc' in column 'q2' is not a number" + fix);
  EXPECT_EQ(ErrorOf(kHeader + "0,0,0,0.1 m,0,0\n"),
            "FILE:2:4: value '0.1 m' in column 'q3' is not a number" + fix);
  EXPECT_EQ(ErrorOf(kHeader + "0,0x10,0,0.1,0,0\n"),
            "FILE:2:2: value '0x10' in column 'q1' is not a number" + fix);
  EXPECT_EQ(ErrorOf("t,q1,q2,q3,tau1,tau2,temp\n0,0,0,0.1,0,0,1e400\n"),
            "FILE:2:7: value '1e400' in column 'temp' is out of the range of a double \u2014 check "
            "the value; magnitudes must lie between about 1e-308 and 1e308 (or be 0)");
  // Not a bad row: skip_bad_rows never hides a malformed file.
  EXPECT_EQ(ErrorOf(kHeader + "0,0,abc,0.1,0,0\n", {true}),
            "FILE:2:3: value 'abc' in column 'q2' is not a number" + fix);
}

TEST_F(LogReaderTest, NonFiniteOrEmptyRequiredValues) {
  EXPECT_EQ(ErrorOf(kHeader + "0,0,0,0.1,,0\n"),
            "FILE:2:5: required column 'tau1' holds no value" + kRequiredFix);
  EXPECT_EQ(ErrorOf(kHeader + "0,nan,0,0.1,0,0\n"),
            "FILE:2:2: required column 'q1' holds 'nan'" + kRequiredFix);
  EXPECT_EQ(ErrorOf(kHeader + "-inf,0,0,0.1,0,0\n"),
            "FILE:2:1: required column 't' holds '-inf'" + kRequiredFix);
  EXPECT_EQ(ErrorOf("t,q1,q2,q3,tau1,tau2,v1\n0,0,0,0.1,0,0,inf\n"),
            "FILE:2:7: column 'v1' holds 'inf' \u2014 write finite values; leave the field empty "
            "when the value is missing");
  const Log log = Read("t,q1,q2,q3,tau1,tau2,v1,aux\n0,0,0,0.1,0,0,nan,NaN\n");
  EXPECT_TRUE(std::isnan(log.Value(0, 6)));
  EXPECT_TRUE(std::isnan(log.Value(0, 7)));
}

TEST_F(LogReaderTest, SkipBadRowsDropsAndCountsThemWithoutMovingTheTimeBaseline) {
  const std::string text = kHeader +
                           "0,0.1,0,0.1,0,0\n"
                           "5,nan,0,0.1,0,0\n"  // skipped: its t must not become the baseline
                           "1,0.2,0,0.1,0,0\n"
                           "2,0.3,0,0.1,,0\n"
                           "3,0.4,0,0.1,0,inf\n";
  LogReader reader(directory_.Write("skip.csv", text), {true});
  std::vector<double> q1;
  while (const double* row = reader.Next()) q1.push_back(row[1]);
  EXPECT_EQ(q1, (std::vector<double>{0.1, 0.2}));
  EXPECT_EQ(reader.skipped_rows(), 3u);
  EXPECT_EQ(reader.rows(), 2u);
  EXPECT_EQ(ErrorOf(kHeader + "0,nan,0,0.1,0,0\n1,0,0,0.1,,0\n", {true}),
            "FILE:3: no usable data rows: all 2 rows were skipped as bad \u2014 give the rows "
            "finite values in t, q1, q2, q3, tau1 and tau2");
}

TEST_F(LogReaderTest, AJointLeftOutOfTheHeaderIsReadAsNotRecorded) {
  const Log log = Read("# timing: quasi-static\nt,q1,q3,tau1,tau1_bias\n0,0.01,0.1,0.5,0.1\n"
                       "1,0.02,0.1,0.6,0.1\n");
  EXPECT_TRUE(log.header.JointRecorded(1));
  EXPECT_FALSE(log.header.JointRecorded(2));
  EXPECT_TRUE(log.header.QuasiStatic());
  // The absent joint's columns come after the file's, all NaN.
  ASSERT_EQ(log.header.columns,
            (std::vector<std::string>{"t", "q1", "q3", "tau1", "tau1_bias", "q2", "tau2"}));
  EXPECT_EQ(log.Column("tau1"), (std::vector<double>{0.5, 0.6}));
  for (double v : log.Column("q2")) EXPECT_TRUE(std::isnan(v));
  for (double v : log.Column("tau2")) EXPECT_TRUE(std::isnan(v));
  const StandardColumns columns(log.header);
  EXPECT_EQ(columns.q2, 5);
  EXPECT_EQ(columns.tau2, 6);
}

TEST_F(LogReaderTest, AJointEmptyInTheFirstRowIsNotRecordedAndMustStayEmpty) {
  const Log log = Read(kHeader + "0,,0.2,0.1,,0.4\n1,nan,0.3,0.1,,0.5\n");
  EXPECT_FALSE(log.header.JointRecorded(1));
  EXPECT_TRUE(log.header.JointRecorded(2));
  EXPECT_FALSE(log.header.QuasiStatic());
  EXPECT_EQ(log.Column("q2"), (std::vector<double>{0.2, 0.3}));
  EXPECT_TRUE(std::isnan(log.Value(1, 1)));
  EXPECT_EQ(ErrorOf(kHeader + "0,0.1,,0.1,0.2,\n\n1,0.1,0.05,0.1,0.2,\n"),
            "FILE:4:3: joint 2 is not recorded (q2 and tau2 are empty in the first data row) but "
            "q2 holds 0.05 here \u2014 give q2 and tau2 on every row, or leave both empty on every "
            "row of a log that records one joint");
  // One of a joint's pair left out is still a missing column, and a row with
  // neither joint is a bad row, not a log of no joint.
  EXPECT_EQ(ErrorOf("t,q1,q3,tau1,tau2\n0,0,0.1,0,0\n"),
            "FILE:1: missing required column 'q2' (joint 2 (pitch) angle in rad); columns found: "
            "t, q1, q3, tau1, tau2 \u2014 add the missing columns, or rename the columns that hold "
            "these quantities");
  EXPECT_EQ(ErrorOf(kHeader + "0,,,0.1,,\n"),
            "FILE:2:2: required column 'q1' holds no value" + kRequiredFix);
  EXPECT_EQ(ErrorOf("t,q1,q3,tau1\n0,,0.1,\n"),
            "FILE:2:2: required column 'q1' holds no value" + kRequiredFix);
}

TEST_F(LogReaderTest, TimeMustIncreaseStrictly) {
  EXPECT_EQ(ErrorOf(kHeader + "0.5,0,0,0.1,0,0\n0.25,0,0,0.1,0,0\n"),
            "FILE:3:1: t = 0.25 s is not greater than the previous row's t = 0.5 s \u2014 t must "
            "be strictly increasing: sort the rows by time and remove repeated samples");
}

TEST_F(LogReaderTest, UnitMistakesAreCaughtByRange) {
  EXPECT_EQ(ErrorOf(kHeader + "0,45,0,0.1,0,0\n"),
            "FILE:2:2: q1 = 45 rad is beyond ±2π rad \u2014 this looks like degrees; convert to "
            "radians (multiply by π/180)");
  EXPECT_EQ(ErrorOf(kHeader + "0,0,-6.3,0.1,0,0\n"),
            "FILE:2:3: q2 = -6.3 rad is beyond ±2π rad \u2014 this looks like degrees; convert to "
            "radians (multiply by π/180)");
  EXPECT_EQ(ErrorOf(kHeader + "0,0,0,150,0,0\n"),
            "FILE:2:4: q3 = 150 m is outside 0–0.3 m \u2014 this looks like millimetres; convert "
            "to metres (divide by 1000)");
  EXPECT_EQ(ErrorOf(kHeader + "0,0,0,-0.01,0,0\n"),
            "FILE:2:4: q3 = -0.01 m is outside 0–0.3 m \u2014 q3 is the insertion depth in metres "
            "and cannot be negative; check the joint 3 sign and offset");
  EXPECT_EQ(ErrorOf(kHeader + "0,0,0,0.1,0,-25\n"),
            "FILE:2:6: tau2 = -25 N·m is beyond ±10 N·m \u2014 likely wrong units: efforts are "
            "N·m (the measured_js effort), not mN·m or motor current");
  const std::string tau1 = "FILE:2:5: tau1 = 10.5 N·m is beyond ±10 N·m \u2014 likely wrong units";
  EXPECT_EQ(ErrorOf(kHeader + "0,0,0,0.1,10.5,0\n").substr(0, tau1.size()), tau1);
  // The limits themselves are accepted.
  EXPECT_EQ(ErrorOf(kHeader + "0,6.28,-6.28,0.3,10,-10\n1,0,0,0,0,0\n"), "no error");
}

// Rows straddle the 1 MiB read chunks; every value and line number must survive.
TEST_F(LogReaderTest, LinesCrossingChunkBoundaries) {
  constexpr int kRows = 50000;  // about 2 MiB
  std::string text = "# k: v\nt,q1,q2,q3,tau1,tau2,aux_channel\n";
  for (int i = 0; i < kRows; ++i) {
    text += std::to_string(i) + ".125,0." + std::to_string(i) + ",-1.5,0.15,2.5," +
            std::to_string(i % 7) + ",123456.789\n";
  }
  ASSERT_GT(text.size(), std::size_t{2} << 20);
  const Log log = Read(text);
  ASSERT_EQ(log.Rows(), static_cast<std::size_t>(kRows));
  for (int i = 0; i < kRows; ++i) {
    ASSERT_EQ(log.Value(i, 0), i + 0.125) << i;
    ASSERT_EQ(log.Value(i, 1), std::stod("0." + std::to_string(i))) << i;
    ASSERT_EQ(log.Value(i, 5), i % 7) << i;
    ASSERT_EQ(log.Value(i, 6), 123456.789) << i;
  }
  text += "49999,0,0,0.1,0,0,1\n";
  const std::string expected =
      "FILE:50003:1: t = 49999 s is not greater than the previous row's t = 49999.125 s \u2014";
  EXPECT_EQ(ErrorOf(text).substr(0, expected.size()), expected);
}

TEST_F(LogReaderTest, LineLongerThanAChunk) {
  const std::string padding(3u << 20, ' ');
  const Log log =
      Read("t,q1,q2,q3,tau1,tau2,aux\n0,1,2,0.1,3,4," + padding + "7\n1,1,2,0.1,3,4,8\n");
  ASSERT_EQ(log.Rows(), 2u);
  EXPECT_EQ(log.Value(0, 6), 7.0);
  EXPECT_EQ(log.Value(1, 6), 8.0);
}

TEST_F(LogReaderTest, AnyChunkSizeReadsTheSameValuesAndLines) {
  const std::string text = "\xEF\xBB\xBF# arm: PSM1\r\nt,q1,q2,q3,tau1,tau2,aux\r\n"
                           "0,0.1,-0.2,0.15,0.5,-0.25,\r\n\r\n0.001,0.2,-0.3,0.16,1.5,2,7\r\n"
                           "0.002,0.2,-0.3,0.16,1.5,2,x\r\n";
  const std::string expected_error =
      "FILE:6:7: value 'x' in column 'aux' is not a number";
  for (std::size_t chunk : {2u, 3u, 7u, 16u, 1u << 20}) {
    LogReaderOptions options;
    options.chunk_bytes = chunk;
    EXPECT_EQ(ErrorOf(text, options).substr(0, expected_error.size()), expected_error) << chunk;
    const Log log = Read(text.substr(0, text.rfind("0.002")), options);
    ASSERT_EQ(log.Rows(), 2u) << chunk;
    EXPECT_EQ(log.header.Metadata("arm"), "PSM1");
    EXPECT_EQ(log.Value(1, 2), -0.3);
    EXPECT_EQ(log.Value(1, 6), 7.0);
    EXPECT_TRUE(std::isnan(log.Value(0, 6)));
  }
}

TEST(TipReference, PrefersTruthThenReferenceThenNone) {
  LogHeader header;
  header.columns = {"t", "q1", "q2", "q3", "tau1", "tau2", "q1_ref", "q2_ref"};
  const TipReference reference = FindTipReference(StandardColumns(header));
  EXPECT_EQ(reference.name, "q*_ref");
  EXPECT_EQ(reference.q1, 6);
  EXPECT_EQ(reference.q2, 7);
  header.columns.insert(header.columns.end(), {"q2_true", "q1_true"});
  const TipReference truth = FindTipReference(StandardColumns(header));
  EXPECT_EQ(truth.name, "q*_true");
  EXPECT_EQ(truth.q1, 9);
  EXPECT_EQ(truth.q2, 8);
  header.columns.resize(6);
  EXPECT_EQ(FindTipReference(StandardColumns(header)).name, "");
  EXPECT_EQ(FindTipReference(StandardColumns(header)).q1, -1);
}

}  // namespace
}  // namespace pliant::io

namespace pliant::io {
namespace {

TEST_F(LogReaderTest, TipFixedIsAFlagAndSegmentACount) {
  const std::string header = "t,q1,q2,q3,tau1,tau2,tip_fixed,segment\n";
  EXPECT_EQ(ErrorOf(header + "0,0,0,0.1,0,0,1,0\n0.1,0,0,0.1,0,0,2,0\n"),
            "FILE:3:7: tip_fixed = 2 is neither 0 nor 1 \u2014 write 1 on rows where the tip is "
            "held still (clamped or in a divot) and 0 elsewhere");
  EXPECT_EQ(ErrorOf(header + "0,0,0,0.1,0,0,0.5,0\n"),
            "FILE:2:7: tip_fixed = 0.5 is neither 0 nor 1 \u2014 write 1 on rows where the tip is "
            "held still (clamped or in a divot) and 0 elsewhere");
  EXPECT_EQ(ErrorOf(header + "0,0,0,0.1,0,0,1,2.5\n"),
            "FILE:2:8: segment = 2.5 is not a whole number \u2014 number the segments 0, 1, 2, "
            "… and give every row its segment's number");
  // Empty (unknown) and whole values read.
  EXPECT_EQ(ErrorOf(header + "0,0,0,0.1,0,0,,\n0.1,0,0,0.1,0,0,0,3\n"), "no error");
}

}  // namespace
}  // namespace pliant::io
