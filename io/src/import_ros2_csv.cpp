// ros2-csv: the CSV files the dVRK's ROS 2 bag extractor writes, one per topic,
// array fields flattened: header.stamp.sec, header.stamp.nanosec, position.0 ...,
// velocity.0 ..., effort.0 ... (name.0 ... too, as text).
//   measured_js -> t (from header.stamp), q1 q2 q3, v1 v2 v3, tau1 tau2 tau3
//   setpoint_js -> q1_cmd q2_cmd q3_cmd: the latest setpoint whose stamp is at
//                  or before the row's measured_js stamp (empty before the first)
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <regex>

#include "import_csv.h"
#include "number_text.h"
#include "pliant/io/import.h"
#include "pliant/io/input_error.h"

namespace pliant::io {
namespace {

constexpr std::string_view kFormat = "ros2-csv";
constexpr double kMissing = std::numeric_limits<double>::quiet_NaN();

struct TopicFile {
  detail::CsvText csv;
  std::vector<std::int64_t> stamp_ns;
  std::vector<double> values;  ///< per row: the topic's columns below
  std::size_t stride = 0;
};

std::string TopicOf(const std::string& path, std::size_t files, const ImportOptions& options) {
  if (!options.topic.empty()) {
    if (files == 1) return options.topic;
    throw InputError("--topic", 0, 0, "--topic names the topic of a single file",
                     "give measured_js and setpoint_js files named after their topics, or import "
                     "one file with --topic");
  }
  const std::string name = detail::FileName(path);
  for (const char* topic : {"measured_js", "setpoint_js"}) {
    if (name.find(topic) != std::string::npos) return topic;
  }
  throw InputError(path, 0, 0, "the file name says neither measured_js nor setpoint_js",
                   "pass --topic measured_js (or setpoint_js), or keep the extractor's file name");
}

// Optional columns are read as NaN when the file has none (an empty array).
std::vector<int> Columns(const detail::CsvText& csv, const std::vector<std::string>& required,
                         const std::vector<std::string>& optional) {
  std::vector<int> read = detail::RequireColumns(csv, required, kFormat);
  for (const auto& name : optional) read.push_back(csv.Index(name));
  return read;
}

TopicFile ReadTopic(const std::string& path, bool measured) {
  TopicFile file{detail::ReadCsv(path), {}, {}, 0};
  std::vector<std::string> required = {"header.stamp.sec", "header.stamp.nanosec", "position.0",
                                       "position.1", "position.2"};
  std::vector<std::string> optional;
  if (measured) {
    required.insert(required.end(), {"effort.0", "effort.1"});
    optional = {"effort.2", "velocity.0", "velocity.1", "velocity.2"};
  }
  const std::vector<int> read = Columns(file.csv, required, optional);
  std::vector<int> present;
  std::copy_if(read.begin(), read.end(), std::back_inserter(present), [](int c) { return c >= 0; });
  const std::vector<double> parsed = detail::ParseColumns(file.csv, present, true);
  file.stride = read.size() - 2;
  for (std::size_t r = 0; r < file.csv.rows.size(); ++r) {
    const double* v = &parsed[r * present.size()];
    for (std::size_t k = 0; k < required.size(); ++k) {
      if (std::isnan(v[k])) {
        throw InputError(path, file.csv.rows[r].line, static_cast<std::size_t>(read[k]) + 1,
                         "column '" + required[k] + "' holds no value",
                         "every message has a stamp, joints 1-3 positions and (measured_js) "
                         "efforts: repair or remove the row");
      }
    }
    const double nanosec = v[1];
    // builtin_interfaces/Time: sec an int32 (a uint32 in ROS 1), nanosec below 1e9.
    if (!(nanosec >= 0.0 && nanosec < 1e9 && std::floor(nanosec) == nanosec &&
          std::floor(v[0]) == v[0] && v[0] >= -2147483648.0 && v[0] <= 4294967295.0)) {
      throw InputError(path, file.csv.rows[r].line, static_cast<std::size_t>(read[0]) + 1,
                       "header.stamp " + detail::NumberText(v[0]) + " s + " +
                           detail::NumberText(nanosec) + " ns is not a ROS time stamp",
                       "sec and nanosec are whole numbers, sec within 32 bits, nanosec below 1e9");
    }
    file.stamp_ns.push_back(static_cast<std::int64_t>(v[0]) * 1000000000 +
                            static_cast<std::int64_t>(nanosec));
    for (std::size_t k = 2, p = 2; k < read.size(); ++k) {
      file.values.push_back(read[k] >= 0 ? v[p++] : kMissing);
    }
  }
  return file;
}

double SecondsSinceFirst(const TopicFile& topic, std::size_t r) {
  return static_cast<double>(topic.stamp_ns[r] - topic.stamp_ns.front()) / 1e9;
}

void CheckMeasured(const TopicFile& measured) {
  const detail::CsvText& csv = measured.csv;
  for (std::size_t r = 0; r < csv.rows.size(); ++r) {
    const double* v = &measured.values[r * measured.stride];
    detail::CheckRange(csv, r, csv.Index("position.2"), v[2], 0.0, 0.3,
                       "position.2 is the PSM insertion depth in metres: import a PSM's topic");
    for (int k : {0, 1}) {
      const std::string name = "position." + std::to_string(k);
      detail::CheckRange(csv, r, csv.Index(name), v[k], -6.283185307179586, 6.283185307179586,
                         "joint angles are in radians: import the arm's measured_js as recorded");
      const std::string effort = "effort." + std::to_string(k);
      detail::CheckRange(csv, r, csv.Index(effort), v[3 + k], -10.0, 10.0,
                         "efforts are in N·m: import the arm's measured_js as recorded");
    }
    if (r > 0 && measured.stamp_ns[r] <= measured.stamp_ns[r - 1]) {
      throw InputError(csv.path, csv.rows[r].line,
                       static_cast<std::size_t>(csv.Index("header.stamp.sec")) + 1,
                       "header.stamp is not after the previous row's",
                       "the rows must be in time order, one per message: sort them by stamp and "
                       "remove repeated messages");
    }
    // t is a double counted from the first stamp: beyond 2^53 ns (104 days) two stamps a
    // nanosecond apart round to the same t, and the log would stand still in time.
    if (r > 0 && !(SecondsSinceFirst(measured, r) > SecondsSinceFirst(measured, r - 1))) {
      throw InputError(csv.path, csv.rows[r].line,
                       static_cast<std::size_t>(csv.Index("header.stamp.sec")) + 1,
                       "header.stamp is " + detail::NumberText(SecondsSinceFirst(measured, r)) +
                           " s after the first row's, too far for its nanoseconds to count",
                       "one recording spans hours, not months: split the file where its stamps "
                       "jump, or remove the stray row");
    }
  }
}

// Decimal seconds, exact to the nanosecond; ROS 2's sec is signed, so a stamp may be
// before 1970 (a clock never set): the sign applies to the whole number.
std::string StampText(std::int64_t stamp_ns) {
  const std::uint64_t magnitude =
      stamp_ns < 0 ? std::uint64_t(0) - std::uint64_t(stamp_ns) : std::uint64_t(stamp_ns);
  std::string fraction = std::to_string(magnitude % 1000000000);
  fraction.insert(0, 9 - fraction.size(), '0');
  return (stamp_ns < 0 ? "-" : "") + std::to_string(magnitude / 1000000000) + "." + fraction;
}

LogHeader MakeHeader(const TopicFile& measured, const TopicFile* setpoint) {
  LogHeader header;
  std::string sources = detail::FileName(measured.csv.path);
  if (setpoint) sources += ", " + detail::FileName(setpoint->csv.path);
  header.metadata = {{"source", sources},
                     {"format", std::string(kFormat)},
                     {"start_time", StampText(measured.stamp_ns.front()) +
                                        " s (header.stamp of the first measured_js row; t counts "
                                        "from it)"}};
  std::smatch arm;
  const std::string name = detail::FileName(measured.csv.path);
  if (std::regex_search(name, arm, std::regex("PSM[0-9]")))
    header.metadata.push_back({"arm", arm.str()});
  if (measured.csv.Index("name.0") >= 0) {
    std::string names;
    for (int k = 0; measured.csv.Index("name." + std::to_string(k)) >= 0; ++k) {
      names +=
          (k ? ", " : "") + measured.csv.Field(0, measured.csv.Index("name." + std::to_string(k)));
    }
    header.metadata.push_back({"joint_names", names});
  }
  header.columns = {"t", "q1", "q2", "q3", "tau1", "tau2", "tau3", "v1", "v2", "v3"};
  if (setpoint) {
    header.metadata.push_back({"setpoint",
                               "q*_cmd = position of the latest setpoint_js row with "
                               "header.stamp at or before the measured_js row's"});
    header.columns.insert(header.columns.end(), {"q1_cmd", "q2_cmd", "q3_cmd"});
  }
  return header;
}

}  // namespace

Log ImportRos2Csv(const std::vector<std::string>& paths, const ImportOptions& options) {
  std::vector<std::string> measured_paths, setpoint_paths;
  for (const auto& path : paths) {
    (TopicOf(path, paths.size(), options) == "measured_js" ? measured_paths : setpoint_paths)
        .push_back(path);
  }
  if (measured_paths.size() != 1 || setpoint_paths.size() > 1) {
    throw InputError(paths.front(), 0, 0,
                     "ros2-csv takes one measured_js file and at most one setpoint_js file; got " +
                         std::to_string(measured_paths.size()) + " and " +
                         std::to_string(setpoint_paths.size()),
                     "import one arm's measured_js.csv, with its setpoint_js.csv if you have it");
  }
  const TopicFile measured = ReadTopic(measured_paths.front(), true);
  CheckMeasured(measured);
  TopicFile setpoint;
  if (!setpoint_paths.empty()) setpoint = ReadTopic(setpoint_paths.front(), false);
  const bool has_setpoint = !setpoint_paths.empty();

  // Setpoint rows by stamp (stable: of equal stamps the later row wins).
  std::vector<std::size_t> setpoint_order(setpoint.stamp_ns.size());
  for (std::size_t s = 0; s < setpoint_order.size(); ++s) setpoint_order[s] = s;
  std::stable_sort(setpoint_order.begin(), setpoint_order.end(), [&](std::size_t a, std::size_t b) {
    return setpoint.stamp_ns[a] < setpoint.stamp_ns[b];
  });

  Log log;
  log.header = MakeHeader(measured, has_setpoint ? &setpoint : nullptr);
  for (std::size_t r = 0; r < measured.stamp_ns.size(); ++r) {
    const double* v = &measured.values[r * measured.stride];
    const double t = SecondsSinceFirst(measured, r);
    // t, q1 q2 q3, tau1 tau2 tau3, v1 v2 v3 (the file's order: position, effort, velocity)
    log.values.insert(log.values.end(), {t, v[0], v[1], v[2], v[3], v[4], v[5], v[6], v[7], v[8]});
    if (!has_setpoint) continue;
    const auto after =
        std::upper_bound(setpoint_order.begin(), setpoint_order.end(), measured.stamp_ns[r],
                         [&](std::int64_t t, std::size_t s) { return t < setpoint.stamp_ns[s]; });
    for (int k = 0; k < 3; ++k) {
      log.values.push_back(after == setpoint_order.begin()
                               ? kMissing
                               : setpoint.values[*(after - 1) * setpoint.stride + k]);
    }
  }
  return log;
}

}  // namespace pliant::io
