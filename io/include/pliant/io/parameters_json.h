#pragma once
// The parameters file (JSON, docs/parameters.md). Unknown keys are errors: a
// typo must never be silently ignored.

#include <string>

#include <nlohmann/json.hpp>

#include "pliant/models/parameters.h"

namespace pliant::io {

/// Reads and validates a parameters file. Throws InputError pointing at the
/// line of the offending key.
models::ModelParameters ReadParameters(const std::string& path);

/// Parses parameters from JSON text; `file` names it in error messages.
models::ModelParameters ParseParameters(const std::string& text, const std::string& file);

nlohmann::json ParametersToJson(const models::ModelParameters& parameters);

/// Writes atomically (see atomic_file.h).
void WriteParameters(const std::string& path, const models::ModelParameters& parameters);

}  // namespace pliant::io
