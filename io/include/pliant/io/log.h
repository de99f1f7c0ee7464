#pragma once
// The canonical pliant log (docs/log-format.md): CSV with one header row,
// optional leading "# key: value" metadata lines, SI units.
//   required: t (s), q1 q2 (rad), q3 (m), tau1 tau2 (N·m)
//   optional: v1 v2 v3, q1_cmd q2_cmd q3_cmd, tau3 (N), q1_ref q2_ref,
//             q1_true q2_true, tip_fixed (0/1), segment (integer)
//   any other numeric column: an auxiliary channel, carried through unchanged.

#include <array>
#include <cstddef>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

namespace pliant::io {

inline constexpr std::array<std::string_view, 6> kRequiredColumns = {"t",  "q1",   "q2",
                                                                      "q3", "tau1", "tau2"};
inline constexpr std::array<std::string_view, 13> kOptionalColumns = {
    "v1",     "v2",     "v3",      "q1_cmd",  "q2_cmd",    "q3_cmd",  "tau3",
    "q1_ref", "q2_ref", "q1_true", "q2_true", "tip_fixed", "segment"};

/// Everything above the data: metadata lines (kept in order, written back) and
/// the column names in file order.
struct LogHeader {
  std::vector<std::pair<std::string, std::string>> metadata;
  std::vector<std::string> columns;
  /// Whether joint 1 and joint 2 are recorded. A log may record one joint only
  /// (a calibration of the joint under test): the other's qJ and tauJ columns are
  /// absent from the file or empty in every row, and read as NaN. Consumers leave
  /// an unrecorded joint at its prior and say so.
  std::array<bool, 2> joint_recorded = {true, true};

  /// joint is 1 or 2.
  bool JointRecorded(int joint) const { return joint_recorded[joint == 2 ? 1 : 0]; }
  /// A log of quasi-static means, one row per pose (metadata "timing: quasi-static"):
  /// t only orders the rows, so no estimator may read dynamics from it.
  bool QuasiStatic() const { return Metadata(kTimingKey) == kQuasiStatic; }

  static constexpr std::string_view kTimingKey = "timing";
  static constexpr std::string_view kQuasiStatic = "quasi-static";

  /// Position of a column in file order, or -1 when the log has none.
  int Index(std::string_view name) const;
  bool Has(std::string_view name) const { return Index(name) >= 0; }
  /// Adds a column at the end, or returns the existing one's index.
  int AddColumn(std::string_view name);
  /// The value of a metadata key, or "" when absent.
  std::string Metadata(std::string_view key) const;
};

/// Indices of the columns every tool reads, resolved once from a header.
struct StandardColumns {
  int t, q1, q2, q3, tau1, tau2;  // always present
  int v1, v2, q1_ref, q2_ref, q1_true, q2_true, tip_fixed, segment;  // -1 when absent
  explicit StandardColumns(const LogHeader& header);
};

/// Where a log says the tip really was, for accuracy reports: simulated truth
/// (q1_true, q2_true) first, else an external reference (q1_ref, q2_ref).
struct TipReference {
  int q1 = -1, q2 = -1;  ///< column indices, -1 when the log has neither
  std::string name;      ///< "q*_true", "q*_ref", or "" when the log has neither
};
TipReference FindTipReference(const StandardColumns& columns);

/// A whole log in memory, row-major: value(row, column).
struct Log {
  LogHeader header;
  std::vector<double> values;

  std::size_t Rows() const;
  std::size_t Columns() const { return header.columns.size(); }
  double Value(std::size_t row, std::size_t column) const;
  /// A copy of one column; throws std::out_of_range naming it when absent.
  std::vector<double> Column(std::string_view name) const;
};

}  // namespace pliant::io
