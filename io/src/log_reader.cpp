#include "pliant/io/log_reader.h"

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <charconv>
#include <cmath>
#include <cstring>
#include <limits>

#include "log_text.h"
#include "pliant/io/atomic_file.h"
#include "pliant/io/progress.h"
#include "number_text.h"

namespace pliant::io {
namespace {

using detail::Quote;
using detail::Trim;

constexpr double kTwoPi = 6.283185307179586;
constexpr double kMaxDepthM = 0.3;
constexpr double kMaxEffortNm = 10.0;

// Indices into LogReader::required_, in kRequiredColumns order.
enum Required { kT, kQ1, kQ2, kQ3, kTau1, kTau2 };

const char kRequiredFix[] =
    "give every row a finite t, q1, q2, q3, tau1 and tau2, or pass --skip-bad-rows (option skip_bad_rows) to drop "
    "and count such rows";

}  // namespace

// A fixed-size window on the file. A line crossing the end of the window is
// moved to its front before the next read, so memory stays at one chunk
// (it grows only for a single line longer than a chunk).
struct LogReader::Buffer {
  int fd = -1;
  std::vector<char> data;
  std::size_t begin = 0, end = 0;
  bool eof = false;
  std::size_t bytes_read = 0;
  std::unique_ptr<Progress> progress;  ///< only while reading, and only on a terminal
  ~Buffer() {
    if (fd >= 0) ::close(fd);
  }
};

LogReader::LogReader(std::string path, LogReaderOptions options)
    : path_(std::move(path)), options_(options), buffer_(std::make_unique<Buffer>()) {
  buffer_->data.resize(std::max<std::size_t>(options_.chunk_bytes, 2));
  // "-" is standard input, named <stdin> in messages.
  const bool standard_input = path_ == kStandardStream;
  if (standard_input) path_ = "<stdin>";
  buffer_->fd = standard_input ? ::fcntl(STDIN_FILENO, F_DUPFD_CLOEXEC, 0)
                               : ::open(path_.c_str(), O_RDONLY | O_CLOEXEC);
  if (buffer_->fd < 0) {
    Fail(0, std::string("cannot open the log (") + std::strerror(errno) + ")",
         "check the path and that the file is readable");
  }
  ShowProgress();
  ReadHeader();
  tip_fixed_column_ = header_.Index("tip_fixed");
  segment_column_ = header_.Index("segment");
  PeekFirstRow();
}

// Megabytes read, of the file's size when it has one (a pipe has not).
void LogReader::ShowProgress() {
  if (!Progress::Enabled()) return;
  struct stat status {};
  const bool sized = ::fstat(buffer_->fd, &status) == 0 && S_ISREG(status.st_mode);
  buffer_->progress = std::make_unique<Progress>(
      "reading " + path_, "MB", sized ? static_cast<double>(status.st_size) / 1e6 : 0.0);
}

LogReader::~LogReader() = default;

void LogReader::Fail(std::size_t column, std::string problem, std::string fix) const {
  throw InputError(path_, line_, column, std::move(problem), std::move(fix));
}

bool LogReader::ReadLine(std::string_view& line) {
  Buffer& b = *buffer_;
  for (;;) {
    char* first = b.data.data() + b.begin;
    const auto* newline = static_cast<char*>(std::memchr(first, '\n', b.end - b.begin));
    if (newline != nullptr || (b.eof && b.begin < b.end)) {
      const char* last = newline != nullptr ? newline : b.data.data() + b.end;
      line = std::string_view(first, static_cast<std::size_t>(last - first));
      b.begin = static_cast<std::size_t>(last - b.data.data()) + (newline != nullptr ? 1 : 0);
      if (!line.empty() && line.back() == '\r') line.remove_suffix(1);
      return true;
    }
    if (b.eof) return false;
    const std::size_t rest = b.end - b.begin;
    std::memmove(b.data.data(), first, rest);
    b.begin = 0;
    b.end = rest;
    if (b.end == b.data.size()) b.data.resize(2 * b.data.size());
    ssize_t got;
    do {
      got = ::read(b.fd, b.data.data() + b.end, b.data.size() - b.end);
    } while (got < 0 && errno == EINTR);
    if (got < 0) {
      Fail(0, std::string("cannot read the log (") + std::strerror(errno) + ")",
           "check that the file is readable and the disk is healthy");
    }
    if (got == 0) b.eof = true;
    b.end += static_cast<std::size_t>(got);
    b.bytes_read += static_cast<std::size_t>(got);
    if (b.progress) b.progress->Set(static_cast<double>(b.bytes_read) / 1e6);
    if (b.eof) b.progress.reset();  // erases the line
  }
}

const double* LogReader::Next() {
  if (finished_) return nullptr;
  std::string_view line;
  while (TakeLine(line)) {
    if (Trim(line).empty()) continue;  // blank lines (e.g. a doubled final newline)
    if (ParseRow(line)) {
      ++rows_;
      return row_.data();
    }
    ++skipped_rows_;
  }
  finished_ = true;
  if (rows_ == 0 && skipped_rows_ == 0) {
    line_ = header_line_;
    Fail(0, "the log has a header but no data rows", "add data rows below the header row");
  }
  if (rows_ == 0) {
    Fail(0,
         "no usable data rows: all " + std::to_string(skipped_rows_) + " rows were skipped as bad",
         "give the rows finite values in t, q1, q2, q3, tau1 and tau2");
  }
  return nullptr;
}

// The row PeekFirstRow read ahead comes first; line_ already counts it.
bool LogReader::TakeLine(std::string_view& line) {
  if (has_pending_) {
    has_pending_ = false;
    line = pending_line_;
    return true;
  }
  if (!ReadLine(line)) return false;
  ++line_;
  return true;
}

void LogReader::FailFieldCount(std::size_t fields) const {
  Fail(0,
       "row has " + std::to_string(fields) + (fields == 1 ? " field" : " fields") +
           " but the header has " + std::to_string(file_columns_) + " columns",
       "every row needs one value per header column; look for a missing or extra comma");
}

bool LogReader::ParseRow(std::string_view line) {
  const char* p = line.data();
  const char* const end = p + line.size();
  const std::size_t columns = file_columns_;
  std::size_t bad_column = 0;  // first required column without a finite value, from 1
  std::string_view bad_text;
  for (std::size_t c = 0; c < columns; ++c) {
    const auto* comma =
        static_cast<const char*>(std::memchr(p, ',', static_cast<std::size_t>(end - p)));
    if (comma == nullptr && c + 1 < columns) {
      FailFieldCount(c + 1);
    }
    const char* field_end = comma != nullptr ? comma : end;
    const std::string_view field =
        Trim(std::string_view(p, static_cast<std::size_t>(field_end - p)));
    double& value = row_[c];
    if (field.empty()) {
      value = std::numeric_limits<double>::quiet_NaN();
    } else {
      const char* first = field.data();
      if (*first == '+' && field.size() > 1 && first[1] != '-') ++first;
      const auto [ptr, ec] = std::from_chars(first, field.data() + field.size(), value);
      if (ptr != field.data() + field.size() ||
          (ec != std::errc() && ec != std::errc::result_out_of_range)) {
        Fail(c + 1,
             "value " + Quote(field) + " in column '" + header_.columns[c] + "' is not a number",
             "write plain decimal numbers such as 0.25 or -1e-3 (no units, quotes or thousands "
             "separators), and remove columns that hold text");
      }
      if (ec == std::errc::result_out_of_range) {
        Fail(c + 1,
             "value " + Quote(field) + " in column '" + header_.columns[c] +
                 "' is out of the range of a double",
             "check the value; magnitudes must lie between about 1e-308 and 1e308 (or be 0)");
      }
    }
    if (!std::isfinite(value) && bad_column == 0) {
      if (is_required_[c] != 0) {
        bad_column = c + 1;
        bad_text = field;
      } else if (std::isinf(value)) {
        Fail(c + 1, "column '" + header_.columns[c] + "' holds " + Quote(field),
             "write finite values; leave the field empty when the value is missing");
      }
    }
    p = field_end + 1;
    if (comma != nullptr && c + 1 == columns) {
      std::size_t fields = columns + 1;
      for (const char* q = p; q < end; ++q) fields += (*q == ',') ? 1 : 0;
      FailFieldCount(fields);
    }
  }
  if (bad_column != 0) {
    if (options_.skip_bad_rows) return false;
    Fail(bad_column,
         "required column '" + header_.columns[bad_column - 1] + "' holds " +
             (bad_text.empty() ? std::string("no value") : Quote(bad_text)),
         kRequiredFix);
  }
  CheckUnrecordedJointsEmpty();
  CheckRanges();
  CheckTipFixedAndSegment();
  return true;
}

// tip_fixed is a flag and segment a count: 2, 0.5 or 2.5 are typing or
// alignment mistakes that would otherwise be read as "not held" or cut a
// segment in two. An empty field (NaN) means unknown and is allowed.
void LogReader::CheckTipFixedAndSegment() const {
  if (tip_fixed_column_ >= 0) {
    const double flag = row_[static_cast<std::size_t>(tip_fixed_column_)];
    if (!std::isnan(flag) && flag != 0.0 && flag != 1.0) {
      Fail(static_cast<std::size_t>(tip_fixed_column_) + 1,
           "tip_fixed = " + detail::NumberText(flag) + " is neither 0 nor 1",
           "write 1 on rows where the tip is held still (clamped or in a divot) and 0 elsewhere");
    }
  }
  if (segment_column_ >= 0) {
    const double segment = row_[static_cast<std::size_t>(segment_column_)];
    if (!std::isnan(segment) && segment != std::floor(segment)) {
      Fail(static_cast<std::size_t>(segment_column_) + 1,
           "segment = " + detail::NumberText(segment) + " is not a whole number",
           "number the segments 0, 1, 2, … and give every row its segment's number");
    }
  }
}

// A joint that the first row left empty stays empty: a value appearing later means
// the rows are misaligned, or the joint was recorded after all.
void LogReader::CheckUnrecordedJointsEmpty() const {
  for (int j = 0; j < 2; ++j) {
    if (header_.joint_recorded[static_cast<std::size_t>(j)]) continue;
    for (int r : {kQ1 + j, kTau1 + j}) {
      const auto column = static_cast<std::size_t>(required_[r]);
      if (column < file_columns_ && !std::isnan(row_[column])) {
        const std::string name(kRequiredColumns[static_cast<std::size_t>(r)]);
        Fail(column + 1,
             "joint " + std::to_string(j + 1) + " is not recorded (q" + std::to_string(j + 1) +
                 " and tau" + std::to_string(j + 1) + " are empty in the first data row) but " +
                 name + " holds " + detail::NumberText(row_[column]) + " here",
             "give q" + std::to_string(j + 1) + " and tau" + std::to_string(j + 1) +
                 " on every row, or leave both empty on every row of a log that records one "
                 "joint");
      }
    }
  }
}

// Unit mistakes (degrees, millimetres, mN·m) are the common failures of real
// logs; they pass any "is it a number" check, so they are caught by range.
void LogReader::CheckRanges() {
  using detail::NumberText;
  const double t = row_[required_[kT]];
  if (have_last_t_ && !(t > last_t_)) {
    Fail(required_[kT] + 1,
         "t = " + NumberText(t) +
             " s is not greater than the previous row's t = " + NumberText(last_t_) + " s",
         "t must be strictly increasing: sort the rows by time and remove repeated samples");
  }
  last_t_ = t;
  have_last_t_ = true;
  for (int r : {kQ1, kQ2}) {
    const double q = row_[required_[r]];
    if (std::abs(q) > kTwoPi) {
      Fail(required_[r] + 1,
           std::string(kRequiredColumns[r]) + " = " + NumberText(q) + " rad is beyond ±2π rad",
           "this looks like degrees; convert to radians (multiply by π/180)");
    }
  }
  const double q3 = row_[required_[kQ3]];
  if (q3 < 0.0 || q3 > kMaxDepthM) {
    Fail(required_[kQ3] + 1, "q3 = " + NumberText(q3) + " m is outside 0–0.3 m",
         q3 > kMaxDepthM ? "this looks like millimetres; convert to metres (divide by 1000)"
                         : "q3 is the insertion depth in metres and cannot be negative; check "
                           "the joint 3 sign and offset");
  }
  for (int r : {kTau1, kTau2}) {
    const double tau = row_[required_[r]];
    if (std::abs(tau) > kMaxEffortNm) {
      Fail(required_[r] + 1,
           std::string(kRequiredColumns[r]) + " = " + NumberText(tau) + " N·m is beyond ±10 N·m",
           "likely wrong units: efforts are N·m (the measured_js effort), not mN·m or motor "
           "current");
    }
  }
}

Log ReadLog(const std::string& path, LogReaderOptions options) {
  LogReader reader(path, options);
  Log log;
  log.header = reader.header();
  const std::size_t columns = log.Columns();
  while (const double* row = reader.Next()) log.values.insert(log.values.end(), row, row + columns);
  return log;
}

}  // namespace pliant::io
