#include "import_csv.h"

#include <cerrno>
#include <charconv>
#include <cmath>
#include <cstring>
#include <fstream>
#include <iterator>
#include <limits>

#include "log_text.h"
#include "number_text.h"
#include "pliant/io/input_error.h"

namespace pliant::io::detail {
namespace {

constexpr std::string_view kByteOrderMark = "\xEF\xBB\xBF";

// Splits one line at commas; fields are trimmed of spaces.
void SplitFields(std::string_view line, std::vector<std::string_view>& fields) {
  fields.clear();
  while (true) {
    const std::size_t comma = line.find(',');
    fields.push_back(Trim(line.substr(0, comma)));
    if (comma == std::string_view::npos) return;
    line.remove_prefix(comma + 1);
  }
}

// Calls visit(line_number, line) for each line, the line end (LF or CRLF) removed.
template <typename Visit>
void ForEachLine(std::string_view text, Visit&& visit) {
  if (text.substr(0, kByteOrderMark.size()) == kByteOrderMark) text.remove_prefix(3);
  std::size_t number = 0;
  while (!text.empty()) {
    const std::size_t end = text.find('\n');
    std::string_view line = text.substr(0, end);
    if (!line.empty() && line.back() == '\r') line.remove_suffix(1);
    if (!visit(++number, line)) return;
    if (end == std::string_view::npos) return;
    text.remove_prefix(end + 1);
  }
}

std::vector<std::string> NamesOf(std::string_view header) {
  std::vector<std::string_view> fields;
  SplitFields(header, fields);
  return {fields.begin(), fields.end()};
}

double ParseField(const CsvText& csv, const CsvText::Row& row, int column, std::string_view field,
                  bool empty_is_missing) {
  const std::string& name = csv.columns[static_cast<std::size_t>(column)];
  const auto fail = [&](const std::string& problem, const std::string& fix) {
    throw InputError(csv.path, row.line, static_cast<std::size_t>(column) + 1, problem, fix);
  };
  if (field.empty()) {
    if (empty_is_missing) return std::numeric_limits<double>::quiet_NaN();
    fail("column '" + name + "' holds no value",
         "every row needs a number in this column: repair or remove the row");
  }
  const char* first = field.data();
  if (*first == '+' && field.size() > 1 && first[1] != '-') ++first;
  double value = 0.0;
  const auto [ptr, ec] = std::from_chars(first, field.data() + field.size(), value);
  if (ptr != field.data() + field.size() || ec != std::errc()) {
    fail("value " + Quote(field) + " in column '" + name + "' is not a finite number",
         "the importer reads plain decimal numbers such as 0.25 or -1e-3: repair the cell, or "
         "check that the file is the format named on stderr");
  }
  if (std::isinf(value)) {
    fail("column '" + name + "' holds " + Quote(field),
         "write finite values; leave the field empty when the value is missing");
  }
  return value;
}

}  // namespace

int CsvText::Index(std::string_view name) const {
  for (std::size_t i = 0; i < columns.size(); ++i) {
    if (columns[i] == name) return static_cast<int>(i);
  }
  return -1;
}

std::string CsvText::ColumnList() const {
  std::string list;
  for (const auto& name : columns) list += (list.empty() ? "" : ", ") + name;
  return list;
}

std::string CsvText::Field(std::size_t row, int column) const {
  std::vector<std::string_view> fields;
  SplitFields(rows[row].text, fields);
  const auto c = static_cast<std::size_t>(column);
  return c < fields.size() ? std::string(fields[c]) : std::string();
}

CsvText ReadCsv(const std::string& path) {
  CsvText csv;
  csv.path = path;
  std::ifstream in(path, std::ios::binary);
  if (!in) {
    throw InputError(path, 0, 0, std::string("cannot open the file (") + std::strerror(errno) + ")",
                     "check the path and that the file is readable");
  }
  csv.content.assign(std::istreambuf_iterator<char>(in), {});
  ForEachLine(csv.content, [&](std::size_t number, std::string_view line) {
    if (Trim(line).empty()) return true;
    if (csv.header_line == 0) {
      csv.header_line = number;
      csv.columns = NamesOf(line);
    } else {
      csv.rows.push_back({number, line});
    }
    return true;
  });
  if (csv.header_line == 0) {
    throw InputError(path, 0, 0, "the file is empty", "give the recording's CSV file");
  }
  if (csv.rows.empty()) {
    throw InputError(path, csv.header_line, 0, "the file has a header row but no data rows",
                     "give the complete recording");
  }
  return csv;
}

std::vector<std::string> ReadCsvHeader(const std::string& path, std::size_t* line_number) {
  std::ifstream in(path, std::ios::binary);
  std::string start(64 * 1024, '\0');
  in.read(start.data(), static_cast<std::streamsize>(start.size()));
  start.resize(static_cast<std::size_t>(in.gcount()));
  std::vector<std::string> names;
  ForEachLine(start, [&](std::size_t number, std::string_view line) {
    // Blank lines and a canonical log's "# key: value" metadata come before a header.
    if (Trim(line).empty() || line.front() == '#') return true;
    *line_number = number;
    names = NamesOf(line);
    return false;
  });
  return names;
}

std::vector<int> RequireColumns(const CsvText& csv, const std::vector<std::string>& names,
                                std::string_view format) {
  std::vector<int> indices;
  for (const auto& name : names) {
    const int index = csv.Index(name);
    if (index < 0) {
      throw InputError(csv.path, csv.header_line, 0,
                       "missing column '" + name + "' of the " + std::string(format) +
                           " format; columns found: " + csv.ColumnList(),
                       "give the file as the recording wrote it, or choose the right format with "
                       "--format (pliant import --help lists them)");
    }
    indices.push_back(index);
  }
  return indices;
}

std::vector<double> ParseColumns(const CsvText& csv, const std::vector<int>& columns,
                                 bool empty_is_missing) {
  std::vector<double> values;
  values.reserve(csv.rows.size() * columns.size());
  std::vector<std::string_view> fields;
  for (const CsvText::Row& row : csv.rows) {
    SplitFields(row.text, fields);
    if (fields.size() != csv.columns.size()) {
      throw InputError(csv.path, row.line, 0,
                       "row has " + std::to_string(fields.size()) + " fields but the header has " +
                           std::to_string(csv.columns.size()) + " columns",
                       "every row needs one value per header column; look for a missing or extra "
                       "comma, or a row cut short");
    }
    for (const int column : columns) {
      values.push_back(
          ParseField(csv, row, column, fields[static_cast<std::size_t>(column)], empty_is_missing));
    }
  }
  return values;
}

void CheckRange(const CsvText& csv, std::size_t row, int column, double value, double low,
                double high, const std::string& fix) {
  if (value >= low && value <= high) return;
  throw InputError(csv.path, csv.rows[row].line, static_cast<std::size_t>(column) + 1,
                   "'" + csv.columns[static_cast<std::size_t>(column)] +
                       "' = " + NumberText(value) + " is outside " + NumberText(low) + " to " +
                       NumberText(high),
                   fix);
}

std::string FileName(const std::string& path) {
  const auto slash = path.find_last_of('/');
  return slash == std::string::npos ? path : path.substr(slash + 1);
}

}  // namespace pliant::io::detail
