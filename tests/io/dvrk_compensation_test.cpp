// The dVRK's own compensation file (dvrk_compensation.h): the real file of the
// JHU group read with its quirks, its numbers checked against the file and the
// component's formulas, write -> read bit-exact, bad files at their line.
#include "pliant/io/dvrk_compensation.h"

#include <gtest/gtest.h>

#include <fstream>
#include <sstream>

#include "pliant/io/input_error.h"
#include "pliant/io/parameters_json.h"
#include "temp_directory.h"

namespace pliant::io {
namespace {

const std::string kRealFile = std::string(PLIANT_SOURCE_DIR) + "/tests/io/data/dvrk-compensation.json";

std::string Text(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  std::ostringstream text;
  text << in.rdbuf();
  return text.str();
}

TEST(DvrkCompensation, TheRealFileIsRecognisedWithItsCommentAndReadAsWritten) {
  const std::string text = Text(kRealFile);
  ASSERT_EQ(text.rfind("/*", 0), 0u) << "the real file starts with a C-style comment";
  EXPECT_TRUE(LooksLikeDvrkCompensation(text));
  const DvrkCompensation c = ParseDvrkCompensation(text, kRealFile);
  const std::array<double, 4> k1 = {-38.3402, 22.6000, -4.5406, 0.3458};
  const std::array<double, 4> k2 = {-16.1879, 9.1018, -1.7220, 0.1343};
  EXPECT_EQ(c.compliance[0], k1);
  EXPECT_EQ(c.compliance[1], k2);
  EXPECT_EQ(c.backlash_rad[0], 0.008478);
  EXPECT_EQ(c.backlash_rad[1], 0.007176);  // stored under "value", not "value-a"
  EXPECT_EQ(c.torque_offset[0][0], 0.199);
  EXPECT_EQ(c.torque_offset[1][0], -0.2419);
  EXPECT_EQ(c.torque_offset[1][1], 0.03458);
}

TEST(DvrkCompensation, ComplianceAndTorqueOffsetAreTheComponentsFormulas) {
  const DvrkCompensation c = ParseDvrkCompensation(Text(kRealFile), kRealFile);
  const auto parameters = DvrkToParameters(c, kRealFile);
  // K1(0.15) = -38.3402·0.15³ + 22.6·0.15² - 4.5406·0.15 + 0.3458, by hand:
  // -0.129398175 + 0.5085 - 0.68109 + 0.3458 = 0.043811825 rad/(N·m).
  EXPECT_NEAR(models::ComplianceAt(parameters.joints[0], 0.15), 0.043811825, 1e-12);
  // K2(0.15) = -0.0546341625 + 0.2047905 - 0.2583 + 0.1343 = 0.0261563375.
  EXPECT_NEAR(models::ComplianceAt(parameters.joints[1], 0.15), 0.0261563375, 1e-12);
  // The component's torque offsets: joint 1 the constant value-a, joint 2
  // value-a·q3 + value-b, at any angle.
  EXPECT_EQ(models::BiasTorqueAt(parameters.joints[0], 0.3, 0.12), 0.199);
  EXPECT_NEAR(models::BiasTorqueAt(parameters.joints[1], -0.2, 0.12), -0.2419 * 0.12 + 0.03458,
              1e-15);
  EXPECT_NEAR(DvrkTorqueOffset(c, 1, 0.12), -0.2419 * 0.12 + 0.03458, 1e-15);
  EXPECT_EQ(parameters.joints[0].backlash_rad, 0.008478);
  EXPECT_EQ(parameters.joints[1].backlash_rad, 0.007176);
}

TEST(DvrkCompensation, WriteThenReadIsBitExactAndSoIsTheTripThroughPliantsParameters) {
  DvrkCompensation c;
  c.compliance = {{{-38.3402, 22.6, -4.5406, 0.1 + 0.2}, {1.0 / 3.0, -2e-17, 5e300, 7.0}}};
  c.torque_offset = {{{0.199, 0.0, 0.0, 0.0}, {-0.2419, 0.03458, 1e-9, -0.0}}};
  c.backlash_rad = {0.008478, 0.1 / 7.0};
  const DvrkCompensation back = ParseDvrkCompensation(DvrkCompensationText(c), "written");
  EXPECT_EQ(back.compliance, c.compliance);
  EXPECT_EQ(back.torque_offset, c.torque_offset);
  EXPECT_EQ(back.backlash_rad, c.backlash_rad);

  // The real file -> pliant's parameters -> the dVRK file: the same numbers
  // (backlash_second now under value-a, the key the component reads).
  const DvrkCompensation real = ParseDvrkCompensation(Text(kRealFile), kRealFile);
  std::vector<std::string> notes;
  const DvrkCompensation trip = ParametersToDvrk(DvrkToParameters(real, kRealFile), &notes);
  EXPECT_EQ(trip.compliance, real.compliance);
  EXPECT_EQ(trip.torque_offset, real.torque_offset);
  EXPECT_EQ(trip.backlash_rad, real.backlash_rad);
  EXPECT_NE(DvrkCompensationText(trip).find("\"parameter\": \"backlash_second\",\n"
                                            "            \"value-a\": 0.007176"),
            std::string::npos);
}

TEST(DvrkCompensation, ThePapersInverseCubicIsWrittenAsAFittedCubicWithItsError) {
  const auto paper = ReadParameters(std::string(PLIANT_SOURCE_DIR) + "/data/paper.json");
  std::vector<std::string> notes;
  const DvrkCompensation c = ParametersToDvrk(paper, &notes);
  for (int j = 0; j < 2; ++j) {
    for (double depth : {0.09, 0.12, 0.155, 0.19, 0.22}) {
      const auto& k = c.compliance[j];
      const double cubic = ((k[0] * depth + k[1]) * depth + k[2]) * depth + k[3];
      // A cubic follows 1/cubic over 0.09–0.22 m to within a few per cent.
      EXPECT_NEAR(cubic / models::ComplianceAt(paper.joints[j], depth), 1.0, 0.05) << depth;
    }
  }
  ASSERT_GE(notes.size(), 2u);
  EXPECT_NE(notes[0].find("joint 1: inverse_cubic K(L) written as a cubic fitted over "
                          "0.090–0.220 m (largest difference"),
            std::string::npos)
      << notes[0];
  // The paper's bias tables are constant in q: joint 1's value, joint 2's value.
  EXPECT_EQ(c.torque_offset[0][0], 0.199);
  EXPECT_NEAR(c.torque_offset[1][1], -0.0029145, 1e-15);
  EXPECT_EQ(c.torque_offset[1][0], 0.0);
}

struct BadFile {
  const char* name;
  const char* text;
  const char* message;
};

TEST(DvrkCompensation, BadFilesAreReportedAtTheirLine) {
  const BadFile cases[] = {
      {"unknown", "/* c */\n{\"parameters\": [\n {\"parameter\": \"compliance_third\", "
                  "\"value-a\": 1}]}",
       "f:3:3: unknown parameter 'compliance_third' — use compliance_first, "
       "torque_offset_first, backlash_first, or the same with _second"},
      {"not_a_number", "{\"parameters\": [\n{\"parameter\": \"backlash_first\",\n \"value-a\": "
                       "\"0.008\"}]}",
       "f:3:2: backlash_first value-a must be a number, found string — write a plain number"},
      {"missing_coefficient",
       "{\"parameters\": [\n {\"parameter\": \"compliance_first\", \"value-a\": 1, \"value-b\": "
       "2, \"value-c\": 3}]}",
       "f:2:2: compliance_first has no \"value-d\" — give all four coefficients a, b, c, d of "
       "K(L) = a·L³ + b·L² + c·L + d"},
      {"missing_entry", "// only one\n{\"parameters\":\n [{\"parameter\": \"backlash_first\", "
                        "\"value-a\": 0.008}]}",
       "f:2:2: no entry for 'compliance_first' — add {\"parameter\": \"compliance_first\", "
       "\"value-a\": …} (docs/parameters.md, 'The dVRK's compensation file')"},
      {"both_spellings", "{\"parameters\": [{\"parameter\": \"backlash_second\",\n \"value\": 1, "
                         "\"value-a\": 2}]}",
       "f:2:2: backlash_second has both \"value\" and \"value-a\" — keep value-a (the key "
       "mtsPSMCompensation reads)"},
      {"syntax", "/* a */ {\"parameters\": [\n {\"parameter\" \"x\"}]}",
       "f:2:17: not valid JSON: syntax error while parsing object separator - unexpected string "
       "literal; expected ':' — fix the syntax here; a missing comma, quote or bracket is the "
       "usual cause"},
  };
  for (const BadFile& c : cases) {
    try {
      ParseDvrkCompensation(c.text, "f");
      ADD_FAILURE() << c.name << " was accepted";
    } catch (const InputError& e) {
      EXPECT_EQ(std::string(e.what()), c.message) << c.name;
    }
  }
}

TEST(DvrkCompensation, APliantFileIsNotTakenForADvrkFile) {
  EXPECT_FALSE(LooksLikeDvrkCompensation(Text(std::string(PLIANT_SOURCE_DIR) + "/data/paper.json")));
  EXPECT_FALSE(LooksLikeDvrkCompensation("not json"));
  EXPECT_FALSE(LooksLikeDvrkCompensation("{\"parameters\": 3}"));
}

TEST(DvrkCompensation, ReadAnyParametersSaysWhichFormatItRead) {
  bool dvrk = false;
  ReadAnyParameters(kRealFile, &dvrk);
  EXPECT_TRUE(dvrk);
  ReadAnyParameters(std::string(PLIANT_SOURCE_DIR) + "/data/paper.json", &dvrk);
  EXPECT_FALSE(dvrk);
}

}  // namespace
}  // namespace pliant::io
