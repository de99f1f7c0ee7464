#pragma once
// The CSV files other tools write, read for import: a header row of names, then
// rows of comma-separated fields (no quoting). Errors name FILE:LINE:COLUMN.

#include <cstddef>
#include <string>
#include <string_view>
#include <vector>

namespace pliant::io::detail {

struct CsvText {
  struct Row {
    std::size_t line;       ///< physical line, from 1
    std::string_view text;  ///< into content, without the line end
  };
  std::string path;
  std::string content;
  std::size_t header_line = 0;
  std::vector<std::string> columns;  ///< header names, trimmed
  std::vector<Row> rows;             ///< non-blank lines after the header

  /// Position of a column, or -1.
  int Index(std::string_view name) const;
  std::string ColumnList() const;  ///< "a, b, c" for messages
  /// The text of one field (trimmed), or "" when the row is shorter.
  std::string Field(std::size_t row, int column) const;
};

/// Reads the whole file. @throws InputError when it cannot be read, is empty or
/// has a header and no rows.
CsvText ReadCsv(const std::string& path);

/// The header names of a file's first non-blank line (at *line), or an empty
/// vector for a file without one; reads at most the first 64 KiB.
std::vector<std::string> ReadCsvHeader(const std::string& path, std::size_t* line);

/// The indices of the named columns. @throws InputError at the header line
/// naming the first missing column, the format and the columns found.
std::vector<int> RequireColumns(const CsvText& csv, const std::vector<std::string>& names,
                                std::string_view format);

/// The numbers in the given columns of every row, row-major (rows × columns.size()).
/// An empty field is NaN when empty_is_missing, else an error; infinities and
/// text are errors, and so is a row with the wrong number of fields.
std::vector<double> ParseColumns(const CsvText& csv, const std::vector<int>& columns,
                                 bool empty_is_missing);

/// @throws InputError at (row, column) when value is outside [low, high].
void CheckRange(const CsvText& csv, std::size_t row, int column, double value, double low,
                double high, const std::string& fix);

/// The part of a path after its last '/'.
std::string FileName(const std::string& path);

}  // namespace pliant::io::detail
