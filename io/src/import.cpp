// The import formats: names, recognition from a file's content, and dispatch.
#include "pliant/io/import.h"

#include <algorithm>
#include <array>
#include <cerrno>
#include <cstring>
#include <fstream>
#include <stdexcept>
#include <utility>

#include "import_csv.h"
#include "pliant/io/input_error.h"

namespace pliant::io {
namespace {

constexpr std::array<std::pair<ImportFormat, std::string_view>, 4> kNames = {{
    {ImportFormat::kJhu2017ClampedBeam, "jhu2017-clamped-beam"},
    {ImportFormat::kJhu2017BiasSweep, "jhu2017-bias-sweep"},
    {ImportFormat::kRos1Bag, "ros1-bag"},
    {ImportFormat::kRos2Csv, "ros2-csv"},
}};

// Columns only one of the two JHU formats has; the columns they share.
const std::vector<std::string> kClampedOnly = {"pos index", "depth", "current joint effort"};
const std::vector<std::string> kBiasOnly = {"position index", "current depth"};
const std::vector<std::string> kJhuShared = {"depth index", "current joint position",
                                             "current torque offset"};

std::size_t CountPresent(const std::vector<std::string>& names,
                         const std::vector<std::string>& header) {
  return static_cast<std::size_t>(std::count_if(names.begin(), names.end(), [&](const auto& n) {
    return std::find(header.begin(), header.end(), n) != header.end();
  }));
}

bool Has(const std::vector<std::string>& header, std::string_view name) {
  return std::find(header.begin(), header.end(), name) != header.end();
}

std::string Joined(const std::vector<std::string>& names) {
  std::string text;
  for (const auto& name : names) text += (text.empty() ? "" : ", ") + name;
  return text;
}

// The format a CSV header row names, or nullopt. A JHU file missing one column
// is still recognised, so that its importer names the missing column.
std::optional<ImportFormat> FormatOfHeader(const std::vector<std::string>& header) {
  const std::size_t shared = CountPresent(kJhuShared, header);
  const std::size_t clamped = CountPresent(kClampedOnly, header);
  const std::size_t bias = CountPresent(kBiasOnly, header);
  if (clamped > bias && shared + clamped >= 4) return ImportFormat::kJhu2017ClampedBeam;
  if (bias > clamped && shared + bias >= 3) return ImportFormat::kJhu2017BiasSweep;
  if (Has(header, "header.stamp.sec") && Has(header, "position.0")) return ImportFormat::kRos2Csv;
  return std::nullopt;
}

bool EndsWith(const std::string& text, std::string_view end) {
  return text.size() >= end.size() && text.compare(text.size() - end.size(), end.size(), end) == 0;
}

}  // namespace

std::string_view ImportFormatName(ImportFormat format) {
  for (const auto& [f, name] : kNames) {
    if (f == format) return name;
  }
  return "unknown";
}

std::optional<ImportFormat> ParseImportFormat(std::string_view name) {
  for (const auto& [format, n] : kNames) {
    if (n == name) return format;
  }
  return std::nullopt;
}

std::string ImportFormatNames() {
  std::string text;
  for (const auto& entry : kNames) text += (text.empty() ? "" : ", ") + std::string(entry.second);
  return text;
}

DetectedFormat DetectImportFormat(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) {
    throw InputError(path, 0, 0, std::string("cannot open the file (") + std::strerror(errno) + ")",
                     "check the path and that the file is readable");
  }
  std::string magic(9, '\0');
  in.read(magic.data(), static_cast<std::streamsize>(magic.size()));
  if (in.gcount() == 9 && magic == "#ROSBAG V") {
    return {ImportFormat::kRos1Bag, "its first bytes, the ROS 1 bag magic '#ROSBAG V'"};
  }
  std::size_t line = 0;
  const std::vector<std::string> header = detail::ReadCsvHeader(path, &line);
  if (const auto format = FormatOfHeader(header)) {
    const std::vector<std::string> first(header.begin(),
                                         header.begin() + std::min<std::size_t>(header.size(), 6));
    const std::string more =
        header.size() > 6 ? ", ... " + std::to_string(header.size()) + " columns" : "";
    return {*format, "its header row: " + Joined(first) + more};
  }
  if (EndsWith(path, ".bag")) return {ImportFormat::kRos1Bag, "its extension .bag"};
  if (EndsWith(path, ".db3") || EndsWith(path, ".mcap")) {
    throw InputError(path, 0, 0, "a ROS 2 bag is not read directly",
                     "extract its topics to CSV with the dVRK's ROS 2 bag extractor and import "
                     "the measured_js CSV (format ros2-csv)");
  }
  if (Has(header, "t") && Has(header, "q3")) {
    throw InputError(path, line, 0, "the file is already a canonical pliant log (t, q3, ...)",
                     "give it to the other pliant commands directly; import reads other formats");
  }
  throw InputError(path, line, 0,
                   "the header row (" + Joined(header).substr(0, 200) +
                       ") matches none of the import formats (" + ImportFormatNames() + ")",
                   "name the format with --format NAME (docs/import.md shows each), or convert "
                   "the file to the canonical log (docs/log-format.md)");
}

Log ImportText(ImportFormat format, const std::vector<std::string>& paths,
               const ImportOptions& options) {
  const auto one_file = [&] {
    if (paths.size() != 1) {
      throw InputError(paths.at(1), 0, 0,
                       std::string(ImportFormatName(format)) + " imports one file at a time",
                       "run pliant import once per file; each writes its own log");
    }
    return paths.front();
  };
  switch (format) {
    case ImportFormat::kJhu2017ClampedBeam:
      return ImportJhu2017ClampedBeam(one_file(), options);
    case ImportFormat::kJhu2017BiasSweep:
      return ImportJhu2017BiasSweep(one_file(), options);
    case ImportFormat::kRos2Csv:
      return ImportRos2Csv(paths, options);
    case ImportFormat::kRos1Bag:
      break;
  }
  throw std::invalid_argument("ImportText: ros1-bag is read by pliant::ros1 (ReadCrtkBag)");
}

}  // namespace pliant::io
