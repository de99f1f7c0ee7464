#pragma once
// Where things are in a JSON text. nlohmann::json keeps no source positions,
// so this small lexer walks the text once and records, for every JSON pointer
// (RFC 6901, e.g. "/joint1/compliance/form"), the line and column of its key
// (object members) or of its first character (array elements). Error messages
// then point at the line the user has to edit.
//
// It is not a validator: on malformed text it stops and keeps what it has
// (nlohmann reports the syntax error). Keys with \u escapes are recorded
// undecoded, so a lookup for them falls back to the enclosing value.

#include <cstddef>
#include <map>
#include <string>
#include <string_view>

namespace pliant::io::detail {

struct JsonPosition {
  std::size_t line = 0;    // from 1
  std::size_t column = 0;  // from 1, in bytes
};

class JsonLocator {
 public:
  explicit JsonLocator(std::string_view text);

  /// Position of `pointer`, or of its nearest ancestor that was found ("" is
  /// the whole document, at its first character).
  JsonPosition Find(std::string pointer) const;

  /// The first key that appears twice in one object (nlohmann would silently
  /// keep the last), as a pointer to its second occurrence; "" when none.
  const std::string& duplicate() const { return duplicate_; }

 private:
  std::map<std::string, JsonPosition> positions_;
  std::string duplicate_;
  JsonPosition duplicate_position_;
};

/// Escapes one reference token of a JSON pointer ("~" -> "~0", "/" -> "~1").
std::string PointerToken(std::string_view key);

/// Line and column (from 1) of a byte offset (from 0) in `text`.
JsonPosition PositionOfOffset(std::string_view text, std::size_t offset);

}  // namespace pliant::io::detail
