#include "pliant/io/input_error.h"

#include <utility>

namespace pliant::io {
namespace {

// One format for every input problem, so editors and CI annotators can jump to it.
std::string Format(const std::string& file, std::size_t line, std::size_t column,
                   const std::string& problem, const std::string& fix) {
  std::string text = file;
  if (line != 0) {
    text += ':' + std::to_string(line);
    if (column != 0) text += ':' + std::to_string(column);
  }
  text += ": " + problem + " \u2014 " + fix;
  return text;
}

}  // namespace

InputError::InputError(std::string file, std::size_t line, std::size_t column, std::string problem,
                       std::string fix)
    : std::runtime_error(Format(file, line, column, problem, fix)),
      file_(std::move(file)),
      line_(line),
      column_(column),
      problem_(std::move(problem)),
      fix_(std::move(fix)) {}

}  // namespace pliant::io
