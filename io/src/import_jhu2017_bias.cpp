// jhu2017-bias-sweep: the JHU 2017 bias-torque sweep CSV (paper Fig. 4), tip free.
//   position index, depth index, current depth, current joint position,
//   current torque offset (the measured effort)
// -> t (row index), qJ, q3, tauJ, tip_fixed = 0, segment, pose_index,
//    depth_index_in_file.
//
// The recording script wrote each depth block's first row before moving the arm
// to the block's depth: that row's measured depth is the previous block's (and
// its angle one more step of the previous sweep), and the file's very first row
// is the arm's start pose, at no block's depth. The measured values are real, so
// a row measured at the previous block's depth keeps them and joins that block
// (segment); a row at no block's depth is dropped. The metadata says which.
#include <algorithm>
#include <cmath>
#include <map>

#include "import_jhu2017.h"
#include "number_text.h"

namespace pliant::io {
namespace {

// Depth blocks are 10 mm apart; q3 holds still within 0.1 mm inside one.
constexpr double kSameDepthM = 0.001;

std::map<double, double> MedianDepthOfBlock(const std::vector<double>& values, std::size_t stride) {
  std::map<double, std::vector<double>> depths;
  for (std::size_t i = 0; i < values.size(); i += stride)
    depths[values[i]].push_back(values[i + 1]);
  std::map<double, double> medians;
  for (auto& [block, d] : depths) {
    std::nth_element(d.begin(), d.begin() + d.size() / 2, d.end());
    medians[block] = d[d.size() / 2];
  }
  return medians;
}

std::string LineList(const std::vector<std::size_t>& lines) {
  std::string text;
  for (std::size_t i = 0; i < lines.size() && i < 20; ++i) {
    text += (i == 0 ? "" : ", ") + std::to_string(lines[i]);
  }
  return lines.size() > 20 ? text + ", ..." : text;
}

}  // namespace

Log ImportJhu2017BiasSweep(const std::string& path, const ImportOptions& options) {
  constexpr ImportFormat kFormat = ImportFormat::kJhu2017BiasSweep;
  const detail::CsvText csv = detail::ReadCsv(path);
  std::vector<std::string> names = detail::JhuSharedColumns(kFormat);
  names.emplace_back("position index");
  const std::vector<int> read = detail::RequireColumns(csv, names, ImportFormatName(kFormat));
  const int joint = detail::JhuJointUnderTest(path, options);
  const std::vector<double> values = detail::ParseColumns(csv, read, false);
  for (std::size_t r = 0; r < csv.rows.size(); ++r) {
    detail::CheckJhuRow(csv, r, read, &values[r * read.size()]);
  }
  const std::map<double, double> median = MedianDepthOfBlock(values, read.size());

  Log log;
  std::vector<std::size_t> relabelled;
  std::string dropped;
  double last_segment = NAN;
  for (std::size_t r = 0; r < csv.rows.size(); ++r) {
    const double* v = &values[r * read.size()];
    double segment = v[0];
    if (std::abs(v[1] - median.at(segment)) > kSameDepthM) {
      if (std::isnan(last_segment) || std::abs(v[1] - median.at(last_segment)) > kSameDepthM) {
        dropped += (dropped.empty() ? "" : "; ") + std::string("line ") +
                   std::to_string(csv.rows[r].line) + " (depth index " + detail::NumberText(v[0]) +
                   "): depth " + detail::NumberText(v[1]) + " m is neither its block's (" +
                   detail::NumberText(median.at(segment)) + " m) nor the previous row's block's";
        continue;
      }
      segment = last_segment;
      relabelled.push_back(csv.rows[r].line);
    }
    last_segment = segment;
    const double t = static_cast<double>(log.values.size() / 8);
    // t, qJ, q3, tauJ, tip_fixed, segment, pose_index, depth_index_in_file
    log.values.insert(log.values.end(), {t, v[2], v[1], v[3], 0.0, segment, v[4], v[0]});
  }

  const std::string j = std::to_string(joint);
  log.header = detail::JhuHeader(
      path, kFormat, joint,
      "bias torque sweep, tip free: joint " + j + " swept over about ±2.2° in small steps at " +
          std::to_string(median.size()) + " insertion depths; tau" + j +
          " is the measured effort (the file's 'current torque offset')");
  log.header.columns.insert(log.header.columns.end(), {"pose_index", "depth_index_in_file"});
  if (!relabelled.empty()) {
    log.header.metadata.emplace_back(
        "relabelled", std::to_string(relabelled.size()) + " rows (lines " + LineList(relabelled) +
                          ") were measured at the previous block's depth, before the arm moved "
                          "on: segment = that block; depth_index_in_file keeps the file's index");
  }
  if (!dropped.empty()) {
    log.header.metadata.emplace_back("dropped", dropped + " (a pose before the sweep began)");
  }
  return log;
}

}  // namespace pliant::io
