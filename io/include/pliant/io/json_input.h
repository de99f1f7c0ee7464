#pragma once
// Every JSON file pliant reads (parameters, scenarios, studies) is parsed here,
// so that every reader reports the same problems the same way, at their line:
// syntax errors, numbers too large for a double, and keys repeated in one
// object (nlohmann would silently keep the last).

#include <optional>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

namespace pliant::io {

/// Parses `text`; `file` names it in messages. Throws InputError.
nlohmann::json ParseJsonInput(const std::string& text, const std::string& file);

/// "/joint1/compliance" -> "joint1.compliance", as users think of a place in a
/// file; "" -> `top`.
std::string DottedJsonPointer(const std::string& pointer, const std::string& top);

/// A key an object may hold.
struct JsonKey {
  const char* name;
  bool required;
};

/// What is wrong at a place in a file, for the reader to report (each reader
/// knows where its values came from: the file, or a --set override).
struct JsonProblem {
  std::string pointer;
  std::string problem;
  std::string fix;
};

/// The first problem with `value` as an object holding only `keys` and every
/// required one, or nullopt. `top` names the file's top level in messages and
/// `see_docs` (e.g. " (docs/parameters.md shows a complete file)") ends the fixes.
std::optional<JsonProblem> CheckJsonObject(const nlohmann::json& value,
                                           const std::string& pointer,
                                           const std::vector<JsonKey>& keys,
                                           const std::string& top, const std::string& see_docs);

}  // namespace pliant::io
