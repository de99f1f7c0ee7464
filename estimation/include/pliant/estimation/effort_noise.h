#pragma once
// The effort's white noise, estimated from a log's own samples (docs/filter.md,
// docs/decisions/effort-noise.md).

#include <vector>

namespace pliant::estimation {

/// The white noise σ (N·m) of one joint's effort sampled at a steady rate:
/// the median absolute second difference over 0.6745·√6. For white noise of
/// σ, τ[k+1] − 2τ[k] + τ[k−1] is N(0, 6σ²); a load or an arm's torque, smooth
/// at a controller's rate, adds next to nothing to it, and the median ignores
/// the few rows where a contact or a reversal does. Never below the effort's
/// quantum over √12 (the smallest step between two samples: a quantised
/// effort that mostly rests has a median second difference of 0). NaN with
/// fewer than kMinNoiseTriples finite triples of consecutive samples.
double EffortNoiseFromSamples(const std::vector<double>& effort_nm);
inline constexpr int kMinNoiseTriples = 50;

}  // namespace pliant::estimation
