#pragma once
// The effort's white noise, and its correlated part, estimated from a log's
// own samples (docs/filter.md, docs/decisions/effort-noise.md,
// docs/decisions/coloured-effort-noise.md).

#include <cstddef>
#include <utility>
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

/// Stretches [begin, end) of rows over which every recorded encoder stays
/// within 1.5 counts of the stretch's first row for at least `min_duration_s`
/// (`times_s`: t). The count is the smallest non-zero encoder step; an
/// encoder that never repeats a value (not quantised: a noisy float) has no
/// stillness to find, and the result is empty. An unrecorded joint's encoder
/// is NaN throughout and is ignored.
std::vector<std::pair<std::size_t, std::size_t>> StillStretches(
    const std::vector<double>& times_s, const std::vector<double> encoder_rad[2],
    double min_duration_s = 0.1);

/// The effort's noise as white plus first-order Gauss–Markov (AR(1) at each
/// sample): its semivariogram over the still stretches, where the load does
/// not change, γ(k) = ½E[(τ[i+k] − τ[i])²] = σ_w² + σ_c²·(1 − exp(−k·dt/τc))
/// for lags k·dt up to 0.15 s, fitted over a grid of τc with (σ_w², σ_c²) by
/// weighted non-negative least squares. Correlated (`found`) only when τc
/// lies between one sample period and a third of the longest lag (shorter:
/// white at this rate; longer: no plateau, a drift the variogram cannot tell
/// from a load) and at least 20 stretches and 2,000 row pairs inform it.
struct EffortNoiseColour {
  bool found = false;
  double white_sd_nm = 0.0, coloured_sd_nm = 0.0, correlation_s = 0.0;
  int stretches = 0;
  std::size_t pairs = 0;  ///< row pairs at lag 1
};
EffortNoiseColour EffortNoiseColourFromStill(
    const std::vector<double>& effort_nm,
    const std::vector<std::pair<std::size_t, std::size_t>>& still, double sample_period_s);

}  // namespace pliant::estimation
