#pragma once
// Shared by the report's HTML and JSON halves.
#include <string>

namespace pliant::experiments::detail {

/// True when a fitted parameter sits on a bound of its catalogue spec (the fit
/// wanted to go further: its value and σ are not an estimate).
bool AtBound(const std::string& effect, const std::string& parameter, double value);

}  // namespace pliant::experiments::detail
