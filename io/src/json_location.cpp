// Public face of the private JSON locator (json_locator.h), for readers in
// other libraries.
#include "pliant/io/json_location.h"

#include "json_locator.h"

namespace pliant::io {

struct JsonSourceMap::Impl {
  explicit Impl(std::string_view text) : locator(text) {}
  detail::JsonLocator locator;
};

JsonSourceMap::JsonSourceMap(std::string_view text) : impl_(std::make_unique<Impl>(text)) {}
JsonSourceMap::~JsonSourceMap() = default;
JsonSourceMap::JsonSourceMap(JsonSourceMap&&) noexcept = default;
JsonSourceMap& JsonSourceMap::operator=(JsonSourceMap&&) noexcept = default;

JsonLocation JsonSourceMap::Find(const std::string& pointer) const {
  const detail::JsonPosition at = impl_->locator.Find(pointer);
  return {at.line, at.column};
}

const std::string& JsonSourceMap::DuplicateKey() const { return impl_->locator.duplicate(); }

std::string JsonPointerToken(std::string_view key) { return detail::PointerToken(key); }

JsonLocation JsonLocationOfOffset(std::string_view text, std::size_t offset) {
  const detail::JsonPosition at = detail::PositionOfOffset(text, offset);
  return {at.line, at.column};
}

}  // namespace pliant::io
