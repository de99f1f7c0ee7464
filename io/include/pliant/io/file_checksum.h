// The CRC-32 of a file's bytes (Boost.CRC): how a parameters file records the
// logs it was fitted on (models::SourceLog), and how a diagnosis knows its log
// among them.
#pragma once

#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "pliant/models/parameters.h"

namespace pliant::io {

/// nullopt for standard input ("-") or a file that cannot be read.
std::optional<std::uint32_t> FileCrc32(const std::string& path);

/// The logs as identify records them: each path with its CRC-32 (those that
/// cannot be read again, as standard input, are left out).
std::vector<models::SourceLog> SourceLogs(const std::vector<std::string>& paths);

/// Adds the logs at `paths` that `parameters` do not yet record (by CRC-32).
void AddSourceLogs(const std::vector<std::string>& paths, models::ModelParameters* parameters);

/// The record among `from` whose CRC-32 is the file's at `path`, if any.
std::optional<models::SourceLog> FittedOn(const std::vector<models::SourceLog>& from,
                                          const std::string& path);

}  // namespace pliant::io
