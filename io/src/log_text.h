#pragma once
// Text helpers shared by the log reader's header and row parsing.

#include <string>
#include <string_view>

namespace pliant::io::detail {

inline std::string_view Trim(std::string_view s) {
  while (!s.empty() && (s.front() == ' ' || s.front() == '\t')) s.remove_prefix(1);
  while (!s.empty() && (s.back() == ' ' || s.back() == '\t')) s.remove_suffix(1);
  return s;
}

// Quotes a field for a message, cut short so one bad row cannot flood a terminal.
inline std::string Quote(std::string_view field) {
  if (field.size() > 40) return "'" + std::string(field.substr(0, 40)) + "...'";
  return "'" + std::string(field) + "'";
}

}  // namespace pliant::io::detail
