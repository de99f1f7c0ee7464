// The part of LogReader above the data: metadata lines and the header row.

#include <limits>

#include "log_text.h"
#include "pliant/io/log_reader.h"

namespace pliant::io {
namespace {

using detail::Quote;
using detail::Trim;

constexpr const char* kRequiredMeaning[] = {"time in s",
                                            "joint 1 (yaw) angle in rad",
                                            "joint 2 (pitch) angle in rad",
                                            "joint 3 insertion depth in m",
                                            "joint 1 effort in N·m",
                                            "joint 2 effort in N·m"};

// 1 or 2 for the required columns of that joint (q1, tau1 / q2, tau2), 0 for t and q3.
int JointOfRequired(std::size_t r) {
  switch (r) {
    case 1: case 4: return 1;
    case 2: case 5: return 2;
    default: return 0;
  }
}

std::string Join(const std::vector<std::string>& names) {
  std::string out;
  for (const auto& name : names) out += (out.empty() ? "" : ", ") + name;
  return out;
}

}  // namespace

void LogReader::ReadHeader() {
  std::string_view line;
  for (;;) {
    if (!ReadLine(line)) {
      if (line_ == 0) {
        Fail(0, "the file is empty",
             "a log needs a header row (t,q1,q2,q3,tau1,tau2) and at least one data row");
      }
      Fail(0, "the file has metadata lines but no header row",
           "add a header row naming the columns (t,q1,q2,q3,tau1,tau2 at least) after the "
           "metadata");
    }
    ++line_;
    if (line_ == 1 && line.substr(0, 3) == "\xEF\xBB\xBF") line.remove_prefix(3);
    if (Trim(line).empty()) continue;
    if (line.front() != '#') break;
    // "# key: value"; a comment without a colon is kept as a key with no value.
    std::string_view text = line.substr(1);
    const std::size_t colon = text.find(':');
    const std::string_view key = Trim(text.substr(0, colon));
    const std::string_view value =
        colon == std::string_view::npos ? std::string_view() : Trim(text.substr(colon + 1));
    header_.metadata.emplace_back(std::string(key), std::string(value));
  }
  header_line_ = line_;
  for (std::size_t start = 0;;) {
    const std::size_t comma = line.find(',', start);
    const std::string_view name = Trim(line.substr(start, comma - start));
    const std::size_t column = header_.columns.size() + 1;
    if (name.empty()) {
      Fail(column, "column " + std::to_string(column) + " of the header has no name",
           "name every column, and remove any trailing comma from the header row");
    }
    const int previous = header_.Index(name);
    if (previous >= 0) {
      Fail(
          column,
          "duplicate column " + Quote(name) + " (also column " + std::to_string(previous + 1) + ")",
          "give every column a distinct name");
    }
    header_.columns.emplace_back(name);
    if (comma == std::string_view::npos) break;
    start = comma + 1;
  }
  // A log may leave out one joint whole (both its angle and its effort): a
  // calibration log records the joint under test only.
  const auto absent = [&](std::string_view a, std::string_view b) {
    return !header_.Has(a) && !header_.Has(b);
  };
  const bool joint_absent[2] = {absent("q1", "tau1"), absent("q2", "tau2")};
  const bool one_joint_absent = joint_absent[0] != joint_absent[1];
  std::vector<std::string> missing;
  for (std::size_t r = 0; r < kRequiredColumns.size(); ++r) {
    const int index = header_.Index(kRequiredColumns[r]);
    const int joint = JointOfRequired(r);
    const bool left_out = one_joint_absent && joint > 0 && joint_absent[joint - 1];
    if (index < 0 && !left_out) {
      missing.push_back("'" + std::string(kRequiredColumns[r]) + "' (" + kRequiredMeaning[r] + ")");
    }
    required_.push_back(index);
  }
  if (!missing.empty()) {
    Fail(0,
         std::string(missing.size() == 1 ? "missing required column "
                                         : "missing required columns ") +
             Join(missing) + "; columns found: " + Join(header_.columns),
         "add the missing columns, or rename the columns that hold these quantities");
  }
  file_columns_ = header_.columns.size();
  AddAbsentJoints();
  is_required_.assign(header_.columns.size(), 0);
  for (std::size_t r = 0; r < required_.size(); ++r) {
    const int joint = JointOfRequired(r);
    if (joint == 0 || header_.JointRecorded(joint)) {
      is_required_[static_cast<std::size_t>(required_[r])] = 1;
    }
  }
  row_.assign(header_.columns.size(), std::numeric_limits<double>::quiet_NaN());
}

// An absent joint's columns are appended, all NaN, so every consumer finds q1..tau2.
void LogReader::AddAbsentJoints() {
  for (std::size_t r = 0; r < kRequiredColumns.size(); ++r) {
    if (required_[r] >= 0) continue;
    header_.joint_recorded[static_cast<std::size_t>(JointOfRequired(r) - 1)] = false;
    required_[r] = header_.AddColumn(kRequiredColumns[r]);
  }
}

// A joint whose angle and effort are both empty (or nan) in the first data row is
// taken as not recorded; the row is kept for Next().
void LogReader::PeekFirstRow() {
  std::string_view line;
  while (ReadLine(line)) {
    ++line_;
    if (Trim(line).empty()) continue;
    pending_line_.assign(line);
    has_pending_ = true;
    break;
  }
  if (!has_pending_) return;
  std::vector<std::string_view> fields;
  for (std::string_view rest = pending_line_;;) {
    const std::size_t comma = rest.find(',');
    fields.push_back(Trim(rest.substr(0, comma)));
    if (comma == std::string_view::npos) break;
    rest.remove_prefix(comma + 1);
  }
  const auto empty = [&](int column) {
    if (column < 0 || static_cast<std::size_t>(column) >= fields.size()) return false;
    const std::string_view f = fields[static_cast<std::size_t>(column)];
    return f.empty() || ((f.size() == 3) && (f[0] | 0x20) == 'n' && (f[1] | 0x20) == 'a' &&
                         (f[2] | 0x20) == 'n');
  };
  bool empty_pair[2];
  for (int j = 0; j < 2; ++j) {
    empty_pair[j] = empty(required_[1 + j]) && empty(required_[4 + j]);
  }
  // Both recorded and exactly one empty: that one is not recorded. Anything else
  // (both empty, or the only joint empty) is a bad row, reported as such.
  if (header_.joint_recorded[0] && header_.joint_recorded[1] && empty_pair[0] != empty_pair[1]) {
    const int j = empty_pair[0] ? 0 : 1;
    header_.joint_recorded[static_cast<std::size_t>(j)] = false;
    is_required_[static_cast<std::size_t>(required_[1 + j])] = 0;
    is_required_[static_cast<std::size_t>(required_[4 + j])] = 0;
  }
}

}  // namespace pliant::io
