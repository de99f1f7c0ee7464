#pragma once
// Where a JSON value sits in its source text, for FILE:LINE error messages in
// readers outside pliant::io (scenario files). nlohmann::json keeps no source
// positions; this maps a JSON pointer (RFC 6901, e.g. "/truth/backlash_rad")
// to the line and column of its key.

#include <cstddef>
#include <memory>
#include <string>
#include <string_view>

namespace pliant::io {

struct JsonLocation {
  std::size_t line = 0;    ///< from 1; 0 when unknown
  std::size_t column = 0;  ///< from 1, in bytes
};

class JsonSourceMap {
 public:
  /// Walks `text` once. Malformed text is mapped as far as it is well formed.
  explicit JsonSourceMap(std::string_view text);
  ~JsonSourceMap();
  JsonSourceMap(JsonSourceMap&&) noexcept;
  JsonSourceMap& operator=(JsonSourceMap&&) noexcept;

  /// Location of `pointer`, or of its nearest ancestor present in the text.
  JsonLocation Find(const std::string& pointer) const;

  /// Pointer to the second occurrence of the first key repeated in one object
  /// (nlohmann silently keeps the last), or "" when there is none.
  const std::string& DuplicateKey() const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

/// One reference token of a JSON pointer, escaped ("~" -> "~0", "/" -> "~1").
std::string JsonPointerToken(std::string_view key);

/// Line and column of a byte offset in `text` (e.g. nlohmann's parse_error::byte − 1).
JsonLocation JsonLocationOfOffset(std::string_view text, std::size_t offset);

}  // namespace pliant::io
