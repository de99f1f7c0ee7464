// jhu2017-clamped-beam: the JHU 2017 clamped-beam CSV (paper §3, Figs. 3 and 5).
//   pos index, depth index, depth, current joint position, current joint effort,
//   current torque offset
// -> t (row index), qJ, q3, tauJ, tip_fixed = 1, segment = depth index,
//    tauJ_bias (the free-space bias torque at that pose), pose_index.
#include <set>

#include "import_jhu2017.h"

namespace pliant::io {

Log ImportJhu2017ClampedBeam(const std::string& path, const ImportOptions& options) {
  constexpr ImportFormat kFormat = ImportFormat::kJhu2017ClampedBeam;
  const detail::CsvText csv = detail::ReadCsv(path);
  std::vector<std::string> names = detail::JhuSharedColumns(kFormat);
  names.insert(names.end(), {"current torque offset", "pos index"});
  const std::vector<int> read = detail::RequireColumns(csv, names, ImportFormatName(kFormat));
  const int joint = detail::JhuJointUnderTest(path, options);
  const std::vector<double> values = detail::ParseColumns(csv, read, false);

  std::set<double> blocks;
  Log log;
  log.values.reserve(csv.rows.size() * 8);
  for (std::size_t r = 0; r < csv.rows.size(); ++r) {
    const double* v = &values[r * read.size()];
    detail::CheckJhuRow(csv, r, read, v);
    blocks.insert(v[0]);
    // t, qJ, q3, tauJ, tip_fixed, segment, tauJ_bias, pose_index
    log.values.insert(log.values.end(),
                      {static_cast<double>(r), v[2], v[1], v[3], 1.0, v[0], v[4], v[5]});
  }
  const std::string j = std::to_string(joint);
  log.header = detail::JhuHeader(
      path, kFormat, joint,
      "clamped beam: the instrument shaft clamped against a rigid beam at " +
          std::to_string(blocks.size()) + " insertion depths (segment = depth index); at each, " +
          "joint " + j + " stepped until its effort passed 1.0 N·m, back past 1.0 N·m the other " +
          "way, then back past the start (pose_index repeats at a reversal). tau" + j +
          "_bias: the free-space bias torque at that pose, from a separate sweep");
  log.header.columns.insert(log.header.columns.end(), {"tau" + j + "_bias", "pose_index"});
  return log;
}

}  // namespace pliant::io
