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
  const io::RecordingFormat chosen = io::ChooseImportFormat(options.inputs, options.format);
  if (!options.format.empty()) {
    std::fprintf(stderr, "pliant import: format %s (--format)\n", options.format.c_str());
  }
  for (const std::string& line : chosen.evidence) {
    std::fprintf(stderr, "pliant import: %s\n", line.c_str());
  }
  return chosen.format;
}

// pliant::ros1's reader, where it was built.
io::BagReader BagReader() {
#ifdef PLIANT_HAVE_ROS1
  return ros::CrtkBagReader();
#else
  return {};
#endif
}

void RunImport(const ImportCommandOptions& options) {
  const io::ImportFormat format = ChooseFormat(options);
  const io::Log log = io::ImportRecording(
      format, options.inputs, {options.joint, options.topic, options.arm}, BagReader());
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
