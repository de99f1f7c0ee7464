// The contact chain's evidence from the effort's level (filter_contact_step.cpp,
// ShareContact): both joints' residuals under contact and under none.
// docs/decisions/contact-scale-free-load.md says why the load's prior is scale-free.
#include <algorithm>
#include <cmath>
#include <limits>

#include "filter_contact_chain.h"

namespace pliant::estimation::filter_internal {

double LogNormal(double x, double v) {
  constexpr double kLogTwoPi = 1.8378770664093453;
  return -0.5 * (x * x / v + std::log(v) + kLogTwoPi);
}

// The load of a contact has a direction (uniform) and a magnitude whose
// scale nobody knows between the table's error at rest (σ_rest, a load it
// hides) and the effort's limit (LevelEvidence passes both): an isotropic
// Gaussian of scale s, log-uniform on [s_lo, s_hi] (the scale-invariant
// prior), s² including the free residual's variance. Integrated over s in
// closed form, with ρ² = |r|² and t = ρ²/(2s²):
//   2 joints: (e^{−t_hi} − e^{−t_lo}) / (2π ρ² ln(s_hi/s_lo)),
//   1 joint:  (erf√t_lo − erf√t_hi) / (2|r| ln(s_hi/s_lo)),
// and at ρ → 0 their limits. A load along one joint is then as likely as the
// same load along both (a slab N(0, σ_c²) per joint charged the still joint
// log(σ_c/σ_free) per look: a light push along joint 1 was never believed).
double ContactLogDensity(double radius2_nm2, int joints, double s_lo2, double s_hi2) {
  constexpr double kPi = 3.14159265358979323846;
  const double log_range = 0.5 * std::log(s_hi2 / s_lo2);
  const double t_lo = 0.5 * radius2_nm2 / s_lo2, t_hi = 0.5 * radius2_nm2 / s_hi2;
  if (joints == 2) {
    if (t_lo < 1e-8) return std::log((0.5 / s_lo2 - 0.5 / s_hi2) / (2.0 * kPi * log_range));
    return std::log(-std::expm1(t_hi - t_lo)) - t_hi - std::log(2.0 * kPi * radius2_nm2 * log_range);
  }
  if (t_lo < 1e-8) {
    return std::log((1.0 / std::sqrt(s_lo2) - 1.0 / std::sqrt(s_hi2)) /
                    (std::sqrt(2.0 * kPi) * log_range));
  }
  const double mass = std::erf(std::sqrt(t_lo)) - std::erf(std::sqrt(t_hi));
  if (!(mass > 0.0)) return -std::numeric_limits<double>::infinity();
  return std::log(mass / (2.0 * std::sqrt(radius2_nm2) * log_range));
}

// A running mean of the change's excess over the model's variance, forgotten
// over 50 pairs (2.5-5 s of free motion), winsorised at 3σ of the pair's free
// law so that one missed contact does not swamp it.
void FreeArmPairChange::Offer(double change_nm, double model_nm2, double free_share) {
  change_nm_ = change_nm, model_nm2_ = model_nm2, share_ = free_share;
}

void FreeArmPairChange::Learn(double free_weight) {
  constexpr double kMemoryPairs = 50.0;
  const double weight = std::clamp(free_weight, 0.0, 1.0) * share_;
  share_ = 0.0;
  if (!(weight > 0.0) || !std::isfinite(change_nm_) || !(model_nm2_ > 0.0)) return;
  lessons_ = std::min(lessons_ + weight, kMemoryPairs);
  const double square = std::min(change_nm_ * change_nm_, 9.0 * (model_nm2_ + variance_));
  variance_ += weight / lessons_ * (std::max(0.0, square - model_nm2_) - variance_);
}

}  // namespace pliant::estimation::filter_internal
