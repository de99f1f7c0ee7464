// The parameters file's "identified_from": the logs a fit read, by path and
// the CRC-32 of their bytes — read, written back, refused with the line of a
// bad value, and matched against a log by its bytes, not its name.
#include <gtest/gtest.h>

#include <fstream>

#include "pliant/io/file_checksum.h"
#include "pliant/io/input_error.h"
#include "pliant/io/parameters_json.h"
#include "pliant/models/paper_parameters.h"
#include "temp_directory.h"

namespace pliant::io {
namespace {

TEST(ParametersSourceLogs, RoundTripKeepsFilesAndChecksums) {
  auto parameters = models::PaperParameters();
  parameters.identified_from = {{"calibration.csv", 0x0000002au}, {"test.csv", 0xdbe6d69bu}};
  const auto json = ParametersToJson(parameters);
  EXPECT_EQ(json.at("identified_from")[0].at("crc32"), "0000002a");  // 8 digits, lower case
  const auto back = ParseParameters(json.dump(2), "p.json");
  ASSERT_EQ(back.identified_from.size(), 2u);
  EXPECT_EQ(back.identified_from[1].file, "test.csv");
  EXPECT_EQ(back.identified_from[1].crc32, 0xdbe6d69bu);
  // Written only when recorded: a hand-written file stays as it was.
  EXPECT_FALSE(ParametersToJson(models::PaperParameters()).contains("identified_from"));
}

TEST(ParametersSourceLogs, AChecksumThatIsNotEightHexDigitsNamesItsLine) {
  auto json = ParametersToJson(models::PaperParameters());
  json["identified_from"] = {{{"file", "a.csv"}, {"crc32", "DBE6D69B"}}};
  try {
    ParseParameters(json.dump(2), "p.json");
    FAIL() << "accepted";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("identified_from.0.crc32 is 'DBE6D69B', not 8 hex digits"),
              std::string::npos)
        << e.what();
    EXPECT_GT(e.line(), 1u);
  }
  json["identified_from"] = "a.csv";
  EXPECT_THROW(ParseParameters(json.dump(2), "p.json"), InputError);
}

// The CRC-32 of "123456789" is the standard check value 0xcbf43926.
TEST(ParametersSourceLogs, ALogIsKnownByItsBytes) {
  const testing::TempDirectory dir;
  const auto write = [&](const char* name, const char* text) {
    const std::string path = (dir.path() / name).string();
    std::ofstream(path) << text;
    return path;
  };
  const std::string log = write("log.csv", "123456789");
  EXPECT_EQ(FileCrc32(log), 0xcbf43926u);
  const auto recorded = SourceLogs({log, "-"});  // standard input cannot be read again
  ASSERT_EQ(recorded.size(), 1u);
  EXPECT_EQ(FittedOn(recorded, write("renamed.csv", "123456789"))->file, log);
  EXPECT_FALSE(FittedOn(recorded, write("other.csv", "123456780")).has_value());
  EXPECT_FALSE(FittedOn({}, log).has_value());
  EXPECT_FALSE(FileCrc32((dir.path() / "missing.csv").string()).has_value());
}

}  // namespace
}  // namespace pliant::io
