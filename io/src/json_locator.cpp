#include "json_locator.h"

#include <algorithm>

namespace pliant::io::detail {
namespace {

// Recursive descent over the JSON grammar, tracking line and column. Depth is
// bounded so a hostile file cannot overflow the stack; nlohmann has its own
// limits for what follows.
class Walker {
 public:
  Walker(std::string_view text, std::map<std::string, JsonPosition>& positions,
         std::string& duplicate, JsonPosition& duplicate_position)
      : text_(text),
        positions_(positions),
        duplicate_(duplicate),
        duplicate_position_(duplicate_position) {}

  void Document() {
    if (text_.substr(0, 3) == "\xEF\xBB\xBF") at_ = line_start_ = 3;  // nlohmann skips a BOM too
    Space();
    positions_[""] = Here();
    Value("", 0);
  }

 private:
  static constexpr int kMaxDepth = 256;

  bool AtEnd() const { return at_ >= text_.size(); }
  char Peek() const { return AtEnd() ? '\0' : text_[at_]; }
  JsonPosition Here() const { return {line_, at_ - line_start_ + 1}; }

  void Advance() {
    if (text_[at_] == '\n') {
      ++line_;
      line_start_ = at_ + 1;
    }
    ++at_;
  }

  void Space() {
    while (!AtEnd() && (Peek() == ' ' || Peek() == '\t' || Peek() == '\n' || Peek() == '\r')) {
      Advance();
    }
  }

  // Returns false on malformed input, which ends the walk.
  bool Value(const std::string& pointer, int depth) {
    if (depth > kMaxDepth || AtEnd()) return false;
    if (Peek() == '{') return Object(pointer, depth);
    if (Peek() == '[') return Array(pointer, depth);
    if (Peek() == '"') {
      std::string ignored;
      return String(ignored);
    }
    const std::size_t start = at_;
    while (!AtEnd() && std::string_view(",]} \t\r\n").find(Peek()) == std::string_view::npos) {
      Advance();
    }
    return at_ > start;
  }

  bool Object(const std::string& pointer, int depth) {
    Advance();  // '{'
    Space();
    if (Peek() == '}') return Advance(), true;
    for (;;) {
      if (Peek() != '"') return false;
      const JsonPosition key_position = Here();
      std::string key;
      if (!String(key)) return false;
      const std::string child = pointer + "/" + PointerToken(key);
      if (!positions_.emplace(child, key_position).second && duplicate_.empty()) {
        duplicate_ = child;
        duplicate_position_ = key_position;
      }
      Space();
      if (Peek() != ':') return false;
      Advance();
      Space();
      if (!Value(child, depth + 1)) return false;
      Space();
      if (Peek() == '}') return Advance(), true;
      if (Peek() != ',') return false;
      Advance();
      Space();
    }
  }

  bool Array(const std::string& pointer, int depth) {
    Advance();  // '['
    Space();
    if (Peek() == ']') return Advance(), true;
    for (std::size_t index = 0;; ++index) {
      const std::string child = pointer + "/" + std::to_string(index);
      positions_.emplace(child, Here());
      if (!Value(child, depth + 1)) return false;
      Space();
      if (Peek() == ']') return Advance(), true;
      if (Peek() != ',') return false;
      Advance();
      Space();
    }
  }

  bool String(std::string& out) {
    Advance();  // '"'
    while (!AtEnd()) {
      const char c = Peek();
      Advance();
      if (c == '"') return true;
      if (c != '\\') {
        out += c;
        continue;
      }
      if (AtEnd()) return false;
      const char e = Peek();
      Advance();
      const std::string_view from = "\"\\/bfnrt", to = "\"\\/\b\f\n\r\t";
      const std::size_t k = from.find(e);
      out += k != std::string_view::npos ? std::string(1, to[k]) : std::string("\\") + e;
    }
    return false;
  }

  std::string_view text_;
  std::map<std::string, JsonPosition>& positions_;
  std::string& duplicate_;
  JsonPosition& duplicate_position_;
  std::size_t at_ = 0, line_ = 1, line_start_ = 0;
};

}  // namespace

JsonLocator::JsonLocator(std::string_view text) {
  Walker(text, positions_, duplicate_, duplicate_position_).Document();
}

JsonPosition JsonLocator::Find(std::string pointer) const {
  // A duplicate is reported at its second occurrence, the one nlohmann kept.
  if (!duplicate_.empty() && pointer == duplicate_) return duplicate_position_;
  for (;;) {
    const auto found = positions_.find(pointer);
    if (found != positions_.end()) return found->second;
    if (pointer.empty()) return {};
    pointer.erase(pointer.rfind('/'));
  }
}

std::string PointerToken(std::string_view key) {
  std::string out;
  for (char c : key) {
    if (c == '~') {
      out += "~0";
    } else if (c == '/') {
      out += "~1";
    } else {
      out += c;
    }
  }
  return out;
}

JsonPosition PositionOfOffset(std::string_view text, std::size_t offset) {
  offset = std::min(offset, text.size());
  const std::string_view before = text.substr(0, offset);
  const std::size_t newlines =
      static_cast<std::size_t>(std::count(before.begin(), before.end(), '\n'));
  const std::size_t line_start = before.rfind('\n');
  const std::size_t column =
      line_start == std::string_view::npos ? offset + 1 : offset - line_start;
  return {newlines + 1, column};
}

}  // namespace pliant::io::detail
