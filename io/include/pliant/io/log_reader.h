#pragma once
// Reading canonical logs: streaming in constant memory for online tools,
// whole-log for offline ones. Every violation of the contract throws
// InputError with the file, line and column, what is wrong and what to do.

#include <cstddef>
#include <cstdio>
#include <memory>
#include <string>
#include <string_view>
#include <vector>

#include "pliant/io/input_error.h"
#include "pliant/io/log.h"

namespace pliant::io {

struct LogReaderOptions {
  /// Drop rows whose required columns hold NaN/Inf or an empty field, and count
  /// them, instead of stopping at the first.
  bool skip_bad_rows = false;
  /// Bytes read at a time; memory stays at one chunk (plus the longest line).
  /// Small chunks are for tests and fuzzing, which exercise lines that cross
  /// chunk boundaries.
  std::size_t chunk_bytes = std::size_t{1} << 20;
};

class LogReader {
 public:
  /// Opens the file ("-": standard input, named "<stdin>" in messages and by
  /// path()) and reads metadata and header. Throws InputError.
  explicit LogReader(std::string path, LogReaderOptions options = {});
  ~LogReader();
  LogReader(const LogReader&) = delete;
  LogReader& operator=(const LogReader&) = delete;

  const LogHeader& header() const { return header_; }
  const std::string& path() const { return path_; }

  /// The next data row's values in header column order, or nullptr at the end
  /// of the file. The pointer stays valid until the next call. Throws InputError
  /// for a bad row, and at the end if the log held no usable data row.
  const double* Next();

  /// Line number (from 1) of the row Next() returned last.
  std::size_t line() const { return line_; }
  /// Rows Next() has returned so far.
  std::size_t rows() const { return rows_; }
  /// Rows dropped under skip_bad_rows.
  std::size_t skipped_rows() const { return skipped_rows_; }

 private:
  struct Buffer;
  bool ReadLine(std::string_view& line);
  bool ParseRow(std::string_view line);
  [[noreturn]] void Fail(std::size_t column, std::string problem, std::string fix) const;
  [[noreturn]] void FailFieldCount(std::size_t fields) const;
  void ReadHeader();
  void ShowProgress();
  void AddAbsentJoints();
  void PeekFirstRow();
  bool TakeLine(std::string_view& line);
  void CheckUnrecordedJointsEmpty() const;
  void CheckRanges();
  void CheckTipFixedAndSegment() const;

  std::string path_;
  LogReaderOptions options_;
  LogHeader header_;
  std::unique_ptr<Buffer> buffer_;
  std::vector<double> row_;
  std::vector<int> required_;      // column index of each required column
  std::vector<char> is_required_;  // per column in file order: 1 when required
  std::size_t file_columns_ = 0;    // columns in the file; absent joints are appended after
  std::string pending_line_;        // the first data row, read ahead to see which joints it has
  bool has_pending_ = false;
  std::size_t line_ = 0;
  std::size_t header_line_ = 0;
  std::size_t rows_ = 0;
  std::size_t skipped_rows_ = 0;
  double last_t_ = 0.0;
  bool have_last_t_ = false;
  bool finished_ = false;
  int tip_fixed_column_ = -1;  // -1 when the log has none
  int segment_column_ = -1;
};

/// Reads a whole log. Throws InputError.
Log ReadLog(const std::string& path, LogReaderOptions options = {});

}  // namespace pliant::io
