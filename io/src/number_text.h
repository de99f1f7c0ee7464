#pragma once
// Shortest round-trip text of a double (std::to_chars): what the writer puts in
// files and what error messages quote, so both show exactly the value read.

#include <charconv>
#include <string>

namespace pliant::io::detail {

inline void AppendNumber(std::string& out, double value) {
  char text[32];  // the longest shortest-form double is 24 characters
  const auto result = std::to_chars(text, text + sizeof text, value);
  out.append(text, result.ptr);
}

inline std::string NumberText(double value) {
  std::string out;
  AppendNumber(out, value);
  return out;
}

}  // namespace pliant::io::detail
