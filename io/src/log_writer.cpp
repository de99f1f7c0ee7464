#include "pliant/io/log_writer.h"

#include <cmath>
#include <stdexcept>

#include "number_text.h"

namespace pliant::io {
namespace {

// Rows are gathered and handed to the file in blocks of about this size.
constexpr std::size_t kBlockBytes = std::size_t{1} << 16;

void CheckText(std::string_view text, std::string_view forbidden, const char* what) {
  if (text.find_first_of(forbidden) != std::string_view::npos) {
    throw std::invalid_argument(std::string(what) + " '" + std::string(text) +
                                "' cannot be written to a log: it holds a character the "
                                "format reserves");
  }
}

}  // namespace

LogWriter::LogWriter(const std::string& path, const LogHeader& header)
    : file_(path), columns_(header.columns.size()) {
  if (columns_ == 0) throw std::invalid_argument("a log needs at least one column: " + path);
  for (const auto& [key, value] : header.metadata) {
    CheckText(key, ":\r\n", "metadata key");
    CheckText(value, "\r\n", "metadata value");
    // A value-less entry is written without the colon, as it was read.
    line_ += value.empty() ? "# " + key + "\n" : "# " + key + ": " + value + "\n";
  }
  for (std::size_t c = 0; c < columns_; ++c) {
    CheckText(header.columns[c], ",\r\n", "column name");
    if (header.columns[c].empty() || header.columns[c].front() == '#') {
      throw std::invalid_argument("column name '" + header.columns[c] + "' cannot be written");
    }
    line_ += (c == 0 ? "" : ",") + header.columns[c];
  }
  line_ += '\n';
}

void LogWriter::Write(const double* values) {
  for (std::size_t c = 0; c < columns_; ++c) {
    if (c != 0) line_ += ',';
    // NaN means "missing" in the canonical log, and missing is an empty field.
    if (!std::isnan(values[c])) detail::AppendNumber(line_, values[c]);
  }
  line_ += '\n';
  if (line_.size() >= kBlockBytes) {
    file_.Write(line_);
    line_.clear();
  }
}

void LogWriter::Commit() {
  file_.Write(line_);
  line_.clear();
  file_.Commit();
}

void WriteLog(const std::string& path, const Log& log) {
  LogWriter writer(path, log.header);
  const std::size_t columns = log.Columns();
  for (std::size_t row = 0; row < log.Rows(); ++row) writer.Write(&log.values[row * columns]);
  writer.Commit();
}

}  // namespace pliant::io
