#pragma once
// Real recordings -> the canonical log (docs/log-format.md, docs/import.md).
//
//   jhu2017-clamped-beam  JHU 2017 clamped-beam CSV (hysteresis_output_joint_N_*.csv)
//   jhu2017-bias-sweep    JHU 2017 bias-torque sweep CSV (small_range_torque_offsets_*.csv)
//   ros1-bag              ROS 1 bag with /ARM/measured_js (read by pliant::ros1, ros/)
//   ros2-csv              the dVRK ROS 2 bag extractor's CSV, one file per topic
//
// The JHU files record one joint, as quasi-static means: their logs leave the
// other joint's q and tau out (LogHeader::JointRecorded) and say
// "# timing: quasi-static", with t the row index. Nothing is invented.

#include <functional>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "pliant/io/log.h"

namespace pliant::io {

enum class ImportFormat { kJhu2017ClampedBeam, kJhu2017BiasSweep, kRos1Bag, kRos2Csv };

/// "jhu2017-clamped-beam", "jhu2017-bias-sweep", "ros1-bag", "ros2-csv".
std::string_view ImportFormatName(ImportFormat format);
/// The format of that name, or nullopt.
std::optional<ImportFormat> ParseImportFormat(std::string_view name);
/// Every format's name, comma-separated (for help and messages).
std::string ImportFormatNames();

struct DetectedFormat {
  ImportFormat format;
  std::string evidence;  ///< what gave it away, e.g. "its header row (pos index, depth index, ...)"
};

/// Recognises a file from its content: the ROS 1 bag magic "#ROSBAG V2.0", then
/// the header row of each CSV format, then the extension (.bag).
/// @throws InputError when the file cannot be read or matches no format.
DetectedFormat DetectImportFormat(const std::string& path);

struct ImportOptions {
  /// JHU files: the PSM joint under test, 1 or 2; 0 = from the file name
  /// ("joint_0" is joint 1, "joint_1" joint 2).
  int joint = 0;
  /// ros2-csv with one file: "measured_js" or "setpoint_js"; "" = from the file name.
  std::string topic;
  /// ros1-bag: the arm, e.g. "PSM2"; "" = the bag's only one (read by the BagReader).
  std::string arm;
};

/// One JHU clamped-beam file: qJ, q3, tauJ, tip_fixed = 1, segment = depth index,
/// tauJ_bias (the file's "current torque offset") and pose_index.
Log ImportJhu2017ClampedBeam(const std::string& path, const ImportOptions& options);

/// One JHU bias sweep (tip free): tauJ = the measured effort. Each depth block's
/// first row was recorded before the arm moved to the block's depth; its segment
/// is the block whose depth it was measured at (depth_index_in_file keeps the
/// file's index), and a row at no block's depth is dropped. Both are stated in
/// the metadata ("relabelled", "dropped").
Log ImportJhu2017BiasSweep(const std::string& path, const ImportOptions& options);

/// The ROS 2 extractor's CSVs: one measured_js file and at most one setpoint_js
/// file, told apart by file name or options.topic.
Log ImportRos2Csv(const std::vector<std::string>& paths, const ImportOptions& options);

/// Imports with one of the text formats above; ros1-bag is not one of them.
/// @throws InputError for bad input, std::invalid_argument for ros1-bag.
Log ImportText(ImportFormat format, const std::vector<std::string>& paths,
               const ImportOptions& options);

/// A recording's format: `format_name` when given (one of ImportFormatNames()),
/// else recognised from each file, all of one format; evidence: per file,
/// "PATH: format NAME (from WHAT)" (empty when named).
/// @throws InputError for an unknown name, an unrecognised file or mixed formats.
struct RecordingFormat {
  ImportFormat format = ImportFormat::kRos2Csv;
  std::vector<std::string> evidence;
};
RecordingFormat ChooseImportFormat(const std::vector<std::string>& paths,
                                   const std::string& format_name);

/// A recording in the chosen format, once its options fit it (an option the
/// format does not read — --arm but for ros1-bag, --joint but for the jhu2017
/// formats, --topic but for ros2-csv — throws InputError naming it): the text
/// formats by ImportText, a ROS 1 bag (one at a time) by read_bag —
/// pliant::ros1's ReadCrtkBag where it was built; without one, an InputError
/// saying how to build it.
using BagReader = std::function<Log(const std::string& path, const std::string& arm)>;
Log ImportRecording(ImportFormat format, const std::vector<std::string>& paths,
                    const ImportOptions& options, const BagReader& read_bag);

}  // namespace pliant::io
