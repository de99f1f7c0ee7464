// The part of LogReader above the data: metadata lines and the header row.

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
  std::vector<std::string> missing;
  for (std::size_t r = 0; r < kRequiredColumns.size(); ++r) {
    const int index = header_.Index(kRequiredColumns[r]);
    if (index < 0) {
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
  is_required_.assign(header_.columns.size(), 0);
  for (int index : required_) is_required_[static_cast<std::size_t>(index)] = 1;
  row_.resize(header_.columns.size());
}

}  // namespace pliant::io
