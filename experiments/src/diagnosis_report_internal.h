#pragma once
// Shared by the report's HTML and JSON halves.
#include <string>

#include "pliant/estimation/diagnosis.h"

namespace pliant::experiments::detail {

/// True when a fitted parameter sits on a bound of its catalogue spec (the fit
/// wanted to go further: its value and σ are not an estimate).
bool AtBound(const std::string& effect, const std::string& parameter, double value);

/// The filter's mean NIS against its 95 % band, in words: inside, above (the
/// filter's errors exceed its noise model: something is missing or the noise
/// is set too low) or below (the noise model is pessimistic).
std::string NisVerdict(const estimation::ResidualStatistics& s);

}  // namespace pliant::experiments::detail
