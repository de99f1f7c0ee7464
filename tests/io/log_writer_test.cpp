#include "pliant/io/log_writer.h"

#include <gtest/gtest.h>

#include <cfloat>
#include <cmath>
#include <cstring>
#include <limits>
#include <random>

#include "pliant/io/log_reader.h"
#include "temp_directory.h"

namespace pliant::io {
namespace {

using testing::ReadText;
using testing::TempDirectory;

std::uint64_t Bits(double value) {
  std::uint64_t bits;
  std::memcpy(&bits, &value, sizeof bits);
  return bits;
}

// Same value and sign bit (so -0 differs from 0); all NaNs are "missing".
void ExpectBitExact(const Log& expected, const Log& actual) {
  ASSERT_EQ(actual.header.metadata, expected.header.metadata);
  ASSERT_EQ(actual.header.columns, expected.header.columns);
  ASSERT_EQ(actual.values.size(), expected.values.size());
  for (std::size_t i = 0; i < expected.values.size(); ++i) {
    if (std::isnan(expected.values[i])) {
      ASSERT_TRUE(std::isnan(actual.values[i])) << "value " << i;
    } else {
      ASSERT_EQ(Bits(actual.values[i]), Bits(expected.values[i]))
          << "value " << i << ": " << expected.values[i] << " read back as " << actual.values[i];
    }
  }
}

TEST(LogWriter, WritesMetadataHeaderShortestNumbersAndEmptyForNaN) {
  TempDirectory directory;
  Log log;
  log.header.metadata = {{"robot", "PSM1"}, {"note", "clamp: rigid"}, {"flag", ""}};
  log.header.columns = {"t", "q1", "q2", "q3", "tau1", "tau2", "v1"};
  log.values = {0.0, 0.1, -0.0, 0.15, 1e-5, 2.5, std::numeric_limits<double>::quiet_NaN()};
  const std::string path = directory.File("out.csv");
  WriteLog(path, log);
  EXPECT_EQ(ReadText(path),
            "# robot: PSM1\n# note: clamp: rigid\n# flag\n"
            "t,q1,q2,q3,tau1,tau2,v1\n"
            "0,0.1,-0,0.15,1e-05,2.5,\n");
}

TEST(LogWriter, RoundTripIsBitExactIncludingAuxiliaryColumnsAndExtremes) {
  TempDirectory directory;
  std::mt19937_64 random(20240611);
  std::uniform_real_distribution<double> angle(-6.28, 6.28), depth(0.0, 0.3), effort(-10, 10);
  Log log;
  log.header.metadata = {{"source", "dvrk ros2 extractor"}, {"clamp", "rigid beam, 0.09 m"}};
  log.header.columns = {"tau2", "t", "q1", "q2", "q3", "tau1", "q1_cmd", "motor_temp", "raw_bits"};
  const double extremes[] = {DBL_TRUE_MIN,
                             -DBL_TRUE_MIN,
                             DBL_MIN,
                             DBL_MAX,
                             -DBL_MAX,
                             -0.0,
                             0.0,
                             1e-310,
                             0.1,
                             1.0 / 3.0,
                             std::nextafter(1.0, 2.0),
                             9007199254740993.0};
  constexpr int kRows = 20000;
  double t = -1000.0;
  for (int row = 0; row < kRows; ++row) {
    t = std::nextafter(t + (row % 3 == 0 ? 0.0 : 0.00066666), 1e9);  // includes 1-ulp steps
    const double bits_value = [&] {
      for (;;) {  // any finite double, subnormals included
        const std::uint64_t bits = random();
        double value;
        std::memcpy(&value, &bits, sizeof value);
        if (std::isfinite(value)) return value;
      }
    }();
    const double q1 = row < 12 ? (row % 2 ? DBL_TRUE_MIN : -0.0) : angle(random);
    const double q1_cmd =
        row % 5 == 0 ? std::numeric_limits<double>::quiet_NaN() : extremes[row % 12];
    log.values.insert(log.values.end(),
                      {effort(random), t, q1, angle(random), depth(random), effort(random), q1_cmd,
                       extremes[(row + 5) % 12], bits_value});
  }
  const std::string first = directory.File("first.csv");
  WriteLog(first, log);
  const Log read = ReadLog(first);
  ExpectBitExact(log, read);
  const std::string second = directory.File("second.csv");
  WriteLog(second, read);
  EXPECT_EQ(ReadText(second), ReadText(first));  // read→write reproduces the bytes
}

TEST(LogWriter, StreamingWriterMatchesWriteLog) {
  TempDirectory directory;
  LogHeader header;
  header.columns = {"t", "q1", "q2", "q3", "tau1", "tau2"};
  LogWriter writer(directory.File("stream.csv"), header);
  for (int row = 0; row < 100000; ++row) {  // more than one 64 KiB block
    const double values[] = {row * 0.001, 0.5, -0.5, 0.12, 0.25, -0.125};
    writer.Write(values);
  }
  writer.Commit();
  const Log log = ReadLog(directory.File("stream.csv"));
  ASSERT_EQ(log.Rows(), 100000u);
  EXPECT_EQ(log.Value(99999, 0), 99999 * 0.001);
  EXPECT_EQ(log.Value(99999, 5), -0.125);
}

TEST(LogWriter, NothingIsLeftWithoutCommit) {
  TempDirectory directory;
  LogHeader header;
  header.columns = {"t", "q1", "q2", "q3", "tau1", "tau2"};
  {
    LogWriter writer(directory.File("out.csv"), header);
    const double values[] = {0, 0, 0, 0.1, 0, 0};
    writer.Write(values);
  }
  EXPECT_TRUE(std::filesystem::is_empty(directory.path()));
}

TEST(LogWriter, RejectsNamesTheFormatCannotHold) {
  TempDirectory directory;
  LogHeader header;
  header.columns = {"t", "q1,q2"};
  EXPECT_THROW(LogWriter(directory.File("a.csv"), header), std::invalid_argument);
  header.columns = {"t"};
  header.metadata = {{"key: with colon", "v"}};
  EXPECT_THROW(LogWriter(directory.File("a.csv"), header), std::invalid_argument);
  header.metadata = {{"key", "two\nlines"}};
  EXPECT_THROW(LogWriter(directory.File("a.csv"), header), std::invalid_argument);
  EXPECT_TRUE(std::filesystem::is_empty(directory.path()));
}

}  // namespace
}  // namespace pliant::io
