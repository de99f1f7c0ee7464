#pragma once
// Every problem with a user's input is reported the same way:
//   FILE:LINE[:COLUMN]: what is wrong — what to do
// and the command exits with status 2 (docs/log-format.md and docs/parameters.md
// list every message).

#include <cstddef>
#include <stdexcept>
#include <string>

namespace pliant::io {

class InputError : public std::runtime_error {
 public:
  /// line and column count from 1; 0 means "not known" and is left out.
  InputError(std::string file, std::size_t line, std::size_t column, std::string problem,
             std::string fix);

  const std::string& file() const { return file_; }
  std::size_t line() const { return line_; }
  std::size_t column() const { return column_; }
  const std::string& problem() const { return problem_; }
  const std::string& fix() const { return fix_; }

 private:
  std::string file_;
  std::size_t line_;
  std::size_t column_;
  std::string problem_;
  std::string fix_;
};

}  // namespace pliant::io
