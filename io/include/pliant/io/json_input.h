#pragma once
// Every JSON file pliant reads (parameters, scenarios, studies) is parsed here,
// so that every reader reports the same problems the same way, at their line:
// syntax errors, numbers too large for a double, and keys repeated in one
// object (nlohmann would silently keep the last).

#include <string>

#include <nlohmann/json.hpp>

namespace pliant::io {

/// Parses `text`; `file` names it in messages. Throws InputError.
nlohmann::json ParseJsonInput(const std::string& text, const std::string& file);

/// "/joint1/compliance" -> "joint1.compliance", as users think of a place in a
/// file; "" -> `top`.
std::string DottedJsonPointer(const std::string& pointer, const std::string& top);

}  // namespace pliant::io
