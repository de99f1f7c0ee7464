// pliant import: real recordings (JHU 2017 CSVs, ROS 1 bags, ROS 2 extractor
// CSVs) to the canonical log, the format recognised from the files' content
// (docs/import.md).
#include <cstdio>
#include <memory>
#include <string>
#include <vector>

#include "commands.h"
#include "pliant/io/import.h"
#include "pliant/io/input_error.h"
#include "pliant/io/log_writer.h"
#ifdef PLIANT_HAVE_ROS1
#include "pliant/ros/crtk_bag.h"
#endif

namespace pliant::cli {
namespace {

struct ImportCommandOptions {
  std::vector<std::string> inputs;
  std::string output_path;
  std::string format;
  std::string arm;
  int joint = 0;
  std::string topic;
};

io::ImportFormat ChooseFormat(const ImportCommandOptions& options) {
  if (!options.format.empty()) {
    const io::ImportFormat format = *io::ParseImportFormat(options.format);
    std::fprintf(stderr, "pliant import: format %s (--format)\n", options.format.c_str());
    return format;
  }
  const io::DetectedFormat first = io::DetectImportFormat(options.inputs.front());
  for (const std::string& path : options.inputs) {
    const io::DetectedFormat detected = io::DetectImportFormat(path);
    if (detected.format != first.format) {
      throw io::InputError(path, 0, 0,
                           "the file is " + std::string(io::ImportFormatName(detected.format)) +
                               " but " + options.inputs.front() + " is " +
                               std::string(io::ImportFormatName(first.format)),
                           "import the files of one recording together, or name the format with "
                           "--format");
    }
    std::fprintf(stderr, "pliant import: %s: format %s (from %s)\n", path.c_str(),
                 std::string(io::ImportFormatName(detected.format)).c_str(),
                 detected.evidence.c_str());
  }
  return first.format;
}

// An option that the chosen format does not read is a mistake, not a no-op.
void CheckOptionsFit(const ImportCommandOptions& options, io::ImportFormat format) {
  const auto refuse = [&](const char* option, const char* format_names) {
    throw io::InputError(option, 0, 0,
                         std::string(option) + " applies to " + format_names + ", not " +
                             std::string(io::ImportFormatName(format)),
                         std::string("leave out ") + option);
  };
  const bool jhu = format == io::ImportFormat::kJhu2017ClampedBeam ||
                   format == io::ImportFormat::kJhu2017BiasSweep;
  if (!options.arm.empty() && format != io::ImportFormat::kRos1Bag) refuse("--arm", "ros1-bag");
  if (options.joint != 0 && !jhu) refuse("--joint", "the jhu2017 formats");
  if (!options.topic.empty() && format != io::ImportFormat::kRos2Csv) refuse("--topic", "ros2-csv");
}

io::Log ReadBag(const ImportCommandOptions& options) {
  const std::string& path = options.inputs.front();
  if (options.inputs.size() != 1) {
    throw io::InputError(options.inputs[1], 0, 0, "ros1-bag imports one bag at a time",
                         "run pliant import once per bag");
  }
#ifdef PLIANT_HAVE_ROS1
  return ros::ReadCrtkBag(path, {options.arm});
#else
  throw io::InputError(path, 0, 0,
                       "this pliant was built without ROS 1 bag support (cmake found no ROS 1: "
                       "see its 'ROS 1 bag support' line)",
                       "install Debian's librosbag-dev libroscpp-dev libsensor-msgs-dev "
                       "(scripts/install-deps.sh does) and rebuild pliant");
#endif
}

void RunImport(const ImportCommandOptions& options) {
  const io::ImportFormat format = ChooseFormat(options);
  CheckOptionsFit(options, format);
  const io::Log log = format == io::ImportFormat::kRos1Bag
                          ? ReadBag(options)
                          : io::ImportText(format, options.inputs, {options.joint, options.topic});
  io::WriteLog(options.output_path, log);
  std::string columns;
  for (const auto& name : log.header.columns) columns += (columns.empty() ? "" : ",") + name;
  std::printf("pliant import: %zu rows -> %s\n  columns: %s\n", log.Rows(),
              options.output_path.c_str(), columns.c_str());
  for (const char* key : {"timing", "joint_recorded", "relabelled", "dropped", "start_time"}) {
    const std::string value = log.header.Metadata(key);
    if (!value.empty()) std::printf("  %s: %s\n", key, value.c_str());
  }
}

}  // namespace

Command AddImportCommand(CLI::App& app) {
  auto options = std::make_shared<ImportCommandOptions>();
  CLI::App* sub = app.add_subcommand(
      "import",
      "Convert real recordings (JHU 2017 CSVs, ROS 1 bags, ROS 2 extractor CSVs) to a log");
  sub->add_option("inputs", options->inputs, "Recording file(s)")->required();
  sub->add_option("-o,--output", options->output_path, "Output log, written atomically")
      ->required();
  sub->add_option("--format", options->format,
                  "Input format (default: recognised from the file): " + io::ImportFormatNames())
      ->check(
          CLI::IsMember({"jhu2017-clamped-beam", "jhu2017-bias-sweep", "ros1-bag", "ros2-csv"}));
  sub->add_option("--arm", options->arm, "ros1-bag: the arm, e.g. PSM2 (default: the only one)");
  sub->add_option("--joint", options->joint,
                  "jhu2017: the PSM joint under test, 1 or 2 (default: from the file name)")
      ->check(CLI::IsMember({1, 2}));
  sub->add_option("--topic", options->topic, "ros2-csv, one file: its topic")
      ->check(CLI::IsMember({"measured_js", "setpoint_js"}));
  return [options] { RunImport(*options); };
}

}  // namespace pliant::cli
