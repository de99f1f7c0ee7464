// CRC-32 of a file (file_checksum.h).
#include "pliant/io/file_checksum.h"

#include <algorithm>
#include <array>
#include <filesystem>
#include <fstream>

#include <boost/crc.hpp>

#include "pliant/io/atomic_file.h"

namespace pliant::io {

std::optional<std::uint32_t> FileCrc32(const std::string& path) {
  // Standard input, a pipe or a device cannot be read again.
  std::error_code error;
  if (path == kStandardStream || !std::filesystem::is_regular_file(path, error)) return std::nullopt;
  std::ifstream in(path, std::ios::binary);
  if (!in) return std::nullopt;
  boost::crc_32_type crc;
  std::array<char, 1 << 16> buffer;
  while (in) {
    in.read(buffer.data(), buffer.size());
    crc.process_bytes(buffer.data(), static_cast<std::size_t>(in.gcount()));
  }
  if (in.bad()) return std::nullopt;
  return crc.checksum();
}

std::vector<models::SourceLog> SourceLogs(const std::vector<std::string>& paths) {
  std::vector<models::SourceLog> out;
  for (const auto& path : paths) {
    if (const auto crc = FileCrc32(path)) out.push_back({path, *crc});
  }
  return out;
}

void AddSourceLogs(const std::vector<std::string>& paths, models::ModelParameters* parameters) {
  auto& recorded = parameters->identified_from;
  for (const auto& log : SourceLogs(paths)) {
    const bool known = std::any_of(recorded.begin(), recorded.end(),
                                   [&](const auto& r) { return r.crc32 == log.crc32; });
    if (!known) recorded.push_back(log);
  }
}

std::optional<models::SourceLog> FittedOn(const std::vector<models::SourceLog>& from,
                                          const std::string& path) {
  if (from.empty()) return std::nullopt;
  const auto crc = FileCrc32(path);
  if (!crc) return std::nullopt;
  for (const auto& log : from) {
    if (log.crc32 == *crc) return log;
  }
  return std::nullopt;
}

}  // namespace pliant::io
