#include "import_jhu2017.h"

#include <cmath>
#include <cstdio>
#include <regex>

#include "number_text.h"
#include "pliant/io/input_error.h"

namespace pliant::io::detail {
namespace {

constexpr double kTwoPi = 6.283185307179586;

// "..._joint_0_2017-7-25-20-30-58.csv": the JHU scripts name the joint under
// test from 0 (PSM joint 1) and stamp the file with the start of the recording.
const std::regex kFileName(
    R"(joint_([01])_(\d{4})-(\d{1,2})-(\d{1,2})-(\d{1,2})-(\d{1,2})-(\d{1,2}))");

std::string RecordedAt(const std::string& path) {
  std::smatch match;
  const std::string name = FileName(path);
  if (!std::regex_search(name, match, kFileName)) return "";
  char text[64];
  std::snprintf(text, sizeof text, "%s-%02d-%02d %02d:%02d:%02d (local time, from the file name)",
                match[2].str().c_str(), std::stoi(match[3]), std::stoi(match[4]),
                std::stoi(match[5]), std::stoi(match[6]), std::stoi(match[7]));
  return text;
}

}  // namespace

int JhuJointUnderTest(const std::string& path, const ImportOptions& options) {
  if (options.joint == 1 || options.joint == 2) return options.joint;
  if (options.joint != 0) {
    throw InputError("--joint", 0, 0, "joint " + std::to_string(options.joint) + " is not 1 or 2",
                     "name the PSM joint under test: 1 (outer yaw) or 2 (outer pitch)");
  }
  std::smatch match;
  const std::string name = FileName(path);
  if (std::regex_search(name, match, std::regex("joint_([01])_"))) {
    return match[1] == "0" ? 1 : 2;
  }
  throw InputError(path, 0, 0,
                   "the file name does not say which joint was under test (the JHU scripts "
                   "write joint_0 for PSM joint 1, joint_1 for joint 2)",
                   "pass --joint 1 or --joint 2");
}

std::vector<std::string> JhuSharedColumns(ImportFormat format) {
  if (format == ImportFormat::kJhu2017ClampedBeam) {
    return {"depth index", "depth", "current joint position", "current joint effort"};
  }
  return {"depth index", "current depth", "current joint position", "current torque offset"};
}

LogHeader JhuHeader(const std::string& path, ImportFormat format, int joint,
                    const std::string& experiment) {
  const std::string j = std::to_string(joint);
  LogHeader header;
  header.metadata = {
      {"source", FileName(path) + " (JHU dvrk-calibration-jhu, commit 2233162, "
                                  "JointForceTesting/ForceTestingDataJointSpace)"},
      {"format", std::string(ImportFormatName(format))},
      {"experiment", experiment},
      {std::string(LogHeader::kTimingKey), std::string(LogHeader::kQuasiStatic)},
      {"rows",
       "each the mean of 20 samples at about 50 Hz, taken after the arm settled 0.5 s; "
       "t is the row index (the file has no time stamps)"},
      {"joint_recorded", j},
      {"joint_not_recorded", std::string(joint == 1 ? "2" : "1") +
                                 " (the file holds nothing of it: its q and tau are absent)"},
  };
  const std::string recorded = RecordedAt(path);
  if (!recorded.empty()) header.metadata.emplace_back("recorded", recorded);
  header.columns = {"t", "q" + j, "q3", "tau" + j, "tip_fixed", "segment"};
  return header;
}

void CheckJhuRow(const CsvText& csv, std::size_t row, const std::vector<int>& read,
                 const double* values) {
  const double block = values[0];
  if (!(block >= 0.0 && std::floor(block) == block)) {
    throw InputError(csv.path, csv.rows[row].line, static_cast<std::size_t>(read[0]) + 1,
                     "depth index " + NumberText(block) + " is not a whole number >= 0",
                     "the depth index counts the insertion depths from 0: repair the cell");
  }
  CheckRange(csv, row, read[1], values[1], 0.0, 0.3,
             "the insertion depth is in metres, 0 to 0.3 m: check the column and its units");
  CheckRange(csv, row, read[2], values[2], -kTwoPi, kTwoPi,
             "the joint angle is in radians: check the column and its units");
  CheckRange(csv, row, read[3], values[3], -10.0, 10.0,
             "the effort is in N·m (the dVRK's limit is 3.3 N·m): check the column and its units");
}

}  // namespace pliant::io::detail
