#pragma once
// The parameters file (JSON, docs/parameters.md). Unknown keys are errors: a
// typo must never be silently ignored.

#include <string>
#include <string_view>

#include <nlohmann/json.hpp>

#include "pliant/models/parameters.h"

namespace pliant::io {

/// The "format" and "version" every parameters file declares.
inline constexpr std::string_view kParametersFormat = "pliant-parameters";
inline constexpr int kParametersVersion = 1;

/// Reads and validates a parameters file. Throws InputError pointing at the
/// line of the offending key.
models::ModelParameters ReadParameters(const std::string& path);

/// The whole text of a parameters file. Throws InputError when it cannot be
/// opened or is a directory.
std::string ReadParametersText(const std::string& path);

/// Parses parameters from JSON text; `file` names it in error messages.
models::ModelParameters ParseParameters(const std::string& text, const std::string& file);

/// The file's JSON (keys in the documented order when dumped via WriteParameters).
/// Throws std::invalid_argument when a JointParameters::sources key names no field.
nlohmann::json ParametersToJson(const models::ModelParameters& parameters);

/// Writes atomically (see atomic_file.h).
void WriteParameters(const std::string& path, const models::ModelParameters& parameters);

}  // namespace pliant::io
