// Which import format a recording's files are in, whether the options given
// fit it, and its import: one rule for `pliant import` and pliant.import_recording.
#include <string>
#include <vector>

#include "pliant/io/import.h"
#include "pliant/io/input_error.h"

namespace pliant::io {

RecordingFormat ChooseImportFormat(const std::vector<std::string>& paths,
                                   const std::string& format_name) {
  if (paths.empty()) {
    throw InputError("inputs", 0, 0, "no recording file given", "name the recording's file(s)");
  }
  RecordingFormat chosen;
  if (!format_name.empty()) {
    const auto format = ParseImportFormat(format_name);
    if (!format) {
      throw InputError(format_name, 0, 0, "no import format is called '" + format_name + "'",
                       "name one of " + ImportFormatNames() + ", or leave the format out");
    }
    chosen.format = *format;
    return chosen;
  }
  const DetectedFormat first = DetectImportFormat(paths.front());
  chosen.format = first.format;
  for (const std::string& path : paths) {
    const DetectedFormat detected = DetectImportFormat(path);
    if (detected.format != first.format) {
      throw InputError(path, 0, 0,
                       "the file is " + std::string(ImportFormatName(detected.format)) + " but " +
                           paths.front() + " is " + std::string(ImportFormatName(first.format)),
                       "import the files of one recording together, or name the format with "
                       "--format");
    }
    chosen.evidence.push_back(path + ": format " + std::string(ImportFormatName(detected.format)) +
                              " (from " + detected.evidence + ")");
  }
  return chosen;
}

namespace {

// An option that the chosen format does not read is a mistake, not a no-op.
void CheckImportOptions(ImportFormat format, const ImportOptions& options) {
  const auto refuse = [&](const char* option, const char* format_names) {
    throw InputError(option, 0, 0,
                     std::string(option) + " applies to " + format_names + ", not " +
                         std::string(ImportFormatName(format)),
                     std::string("leave out ") + option);
  };
  const bool jhu =
      format == ImportFormat::kJhu2017ClampedBeam || format == ImportFormat::kJhu2017BiasSweep;
  if (!options.arm.empty() && format != ImportFormat::kRos1Bag) refuse("--arm", "ros1-bag");
  if (options.joint != 0 && !jhu) refuse("--joint", "the jhu2017 formats");
  if (!options.topic.empty() && format != ImportFormat::kRos2Csv) refuse("--topic", "ros2-csv");
}

}  // namespace

Log ImportRecording(ImportFormat format, const std::vector<std::string>& paths,
                    const ImportOptions& options, const BagReader& read_bag) {
  CheckImportOptions(format, options);
  if (format != ImportFormat::kRos1Bag) return ImportText(format, paths, options);
  if (paths.size() != 1) {
    throw InputError(paths.at(1), 0, 0, "ros1-bag imports one bag at a time",
                     "run pliant import once per bag");
  }
  if (!read_bag) {
    throw InputError(paths.front(), 0, 0,
                     "this pliant was built without ROS 1 bag support (cmake's 'ROS 1 bag "
                     "support' line says why)",
                     "install Debian's librosbag-dev libroscpp-dev libsensor-msgs-dev "
                     "(scripts/install-deps.sh does) and rebuild pliant");
  }
  return read_bag(paths.front(), options.arm);
}

}  // namespace pliant::io
