#pragma once
// An output's destination is checked before any work: a missing or read-only
// directory found after three seconds of identification (or a whole
// simulation) wastes them, and the temporary file's error does not say what
// to do.

#include <string>

namespace pliant::io {

/// Throws InputError naming `option` (e.g. "-o") when the directory that would
/// hold `path` is missing, is not a directory, or is not writable, or when
/// `path` itself is a directory. An empty `path` (no output asked) passes.
void CheckOutputFile(const std::string& path, const std::string& option);

/// The same for an output directory (created if missing): its nearest
/// existing ancestor must be a writable directory, and `path` must not be a file.
void CheckOutputDirectory(const std::string& path, const std::string& option);

}  // namespace pliant::io
