#include "pliant/io/json_input.h"

#include "json_locator.h"
#include "pliant/io/input_error.h"

namespace pliant::io {
namespace {

using nlohmann::json;

[[noreturn]] void ThrowSyntaxError(const json::parse_error& error, const std::string& text,
                                   const std::string& file) {
  // nlohmann's byte is 1-based: the position of the last character it read.
  const auto at = detail::PositionOfOffset(text, error.byte == 0 ? 0 : error.byte - 1);
  std::string message = error.what();
  const std::size_t colon = message.find(": ", message.find("parse error"));
  if (colon != std::string::npos) message = message.substr(colon + 2);
  throw InputError(file, at.line, at.column, "not valid JSON: " + message,
                   "fix the syntax here; a missing comma, quote or bracket is the usual cause");
}

// A number too large for a double (found by fuzzing both the parameters and the
// scenario readers): nlohmann gives no position but quotes the literal, which
// is then found in the text.
[[noreturn]] void ThrowNumberOverflow(const json::out_of_range& error, const std::string& text,
                                      const std::string& file) {
  const std::string message = error.what();
  const std::size_t open = message.find('\'');
  const std::size_t close = message.rfind('\'');
  const std::string literal =
      open < close ? message.substr(open + 1, close - open - 1) : std::string();
  const std::size_t offset = literal.empty() ? std::string::npos : text.find(literal);
  const auto at = offset == std::string::npos ? detail::JsonPosition{}
                                              : detail::PositionOfOffset(text, offset);
  throw InputError(file, at.line, at.column,
                   "number " + (literal.empty() ? std::string("value") : literal) +
                       " does not fit in a double",
                   "write a number between -1.7e308 and 1.7e308");
}

}  // namespace

std::string DottedJsonPointer(const std::string& pointer, const std::string& top) {
  if (pointer.empty()) return top;
  std::string out = pointer.substr(1);
  for (char& c : out) c = c == '/' ? '.' : c;
  return out;
}

json ParseJsonInput(const std::string& text, const std::string& file) {
  json document;
  try {
    document = json::parse(text);
  } catch (const json::parse_error& error) {
    ThrowSyntaxError(error, text, file);
  } catch (const json::out_of_range& error) {
    ThrowNumberOverflow(error, text, file);
  }
  const detail::JsonLocator locator(text);
  const std::string& pointer = locator.duplicate();
  if (!pointer.empty()) {
    const detail::JsonPosition at = locator.Find(pointer);
    const std::size_t slash = pointer.rfind('/');
    throw InputError(file, at.line, at.column,
                     "duplicate key '" + pointer.substr(slash + 1) + "' in " +
                         DottedJsonPointer(pointer.substr(0, slash), "the top-level object"),
                     "keep only one; JSON readers silently use the last and ignore the others");
  }
  return document;
}

std::optional<JsonProblem> CheckJsonObject(const json& value, const std::string& pointer,
                                           const std::vector<JsonKey>& keys,
                                           const std::string& top, const std::string& see_docs) {
  const std::string here = DottedJsonPointer(pointer, top);
  if (!value.is_object()) {
    return JsonProblem{pointer, here + " must be an object, found " + value.type_name(),
                       "write it as { ... }" + see_docs};
  }
  std::string allowed;
  for (const JsonKey& key : keys) allowed += (allowed.empty() ? "" : ", ") + std::string(key.name);
  for (const auto& item : value.items()) {
    bool known = false;
    for (const JsonKey& key : keys) known = known || item.key() == key.name;
    if (!known) {
      return JsonProblem{pointer + "/" + detail::PointerToken(item.key()),
                         "unknown key '" + item.key() + "' in " + here + "; allowed keys: " + allowed,
                         "remove the key or correct its spelling"};
    }
  }
  for (const JsonKey& key : keys) {
    if (key.required && !value.contains(key.name)) {
      return JsonProblem{pointer, here + " has no key '" + key.name + "'",
                         "add \"" + std::string(key.name) + "\"" + see_docs};
    }
  }
  return std::nullopt;
}

}  // namespace pliant::io
