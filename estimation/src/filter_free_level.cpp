// The free level (filter_free_level.h).
#include "filter_free_level.h"

#include <algorithm>
#include <cmath>

#include "filter_contact_chain.h"

namespace pliant::estimation::filter_internal {

void FreeLevel::Start(const FilterOptions& o, double equilibrium_nm2) {
  on = o.free_level && !o.quasi_static;
  mean = 0.0;
  variance = equilibrium_nm2;
  still = 1.0;
  inverse_length_ << 1.0 / o.free_level_length_rad, 1.0 / o.free_level_length_rad,
      1.0 / o.free_level_depth_length_m;
  pose_.setZero(), anchor_pose_.setZero();
  anchored_ = false;
  time_s_ = anchor_time_s_ = anchor_mean_ = anchor_variance_ = 0.0;
  drift2_ = o.free_level_drift_nm * o.free_level_drift_nm;
  rest2_ = o.unmodelled_effort_sd_nm * o.unmodelled_effort_sd_nm;
  noise2_ = o.effort_noise_nm * o.effort_noise_nm;
  limit2_ = o.effort_limit_nm * o.effort_limit_nm;
}

// A smooth field (the table's error is a smooth function of the pose):
// squared-exponential in the scaled distance. z carries the effort's noise
// through s·K(L), a milliradian a row, which a rough field's e^(−d/L) would
// read as travel that forgets a few per cent of the level on every row.
double FreeLevel::Correlation(const Eigen::Vector3d& a, const Eigen::Vector3d& b) const {
  return std::exp(-0.5 * (a - b).cwiseProduct(inverse_length_).squaredNorm());
}

// The field is known where it was last taught (the anchor); elsewhere by its
// correlation with the anchor, and it drifts in time. A distance from the
// anchor, not a path's length: summed over rows, z's noise alone is metres.
void FreeLevel::Predict(const Eigen::Vector3d& pose, double dt_s, double still_share,
                        double equilibrium_nm2) {
  if (!on) return;
  still = std::isfinite(still_share) ? std::clamp(still_share, 0.0, 1.0) : 0.0;
  if (dt_s > 0.0 && std::isfinite(dt_s)) time_s_ += dt_s;
  // A row without a depth (or an angle) leaves the level where it was.
  for (int k = 0; k < 3; ++k) {
    if (std::isfinite(pose[k])) pose_[k] = pose[k];
  }
  const double keep = anchored_ ? Correlation(pose_, anchor_pose_) : 0.0;
  mean = keep * anchor_mean_;
  variance = keep * keep * anchor_variance_ + (1.0 - keep * keep) * equilibrium_nm2 +
             drift2_ * (time_s_ - anchor_time_s_);
}

// A lesson reaches the level through the field's correlation between the
// batch's pose and this row's (the change counts as its noise). Its noise is
// one row's effort noise, which no correlation between rows can exceed. And
// a lesson the field cannot have made (a change far beyond what it allows)
// is a load's: its weight is the chance that it is the field's, against a
// load of any scale from σ_rest up (ContactLogDensity), at even odds — a
// light push the chain has not yet believed teaches the level nothing.
void FreeLevel::Teach(double residual_nm, const Eigen::Vector3d& pose, double weight,
                      double equilibrium_nm2) {
  if (!on || !(weight > 1e-3) || !std::isfinite(residual_nm) || !pose.allFinite()) return;
  const double keep = Correlation(pose_, pose);
  const double noise = noise2_ + (1.0 - keep * keep) * equilibrium_nm2;
  const double innovation = residual_nm - mean, spread = variance + noise;
  const double field = LogNormal(innovation, spread);
  const double load = ContactLogDensity(innovation * innovation, 1, rest2_ + spread, limit2_ + spread);
  const double fits = 1.0 / (1.0 + std::exp(std::clamp(load - field, -700.0, 700.0)));
  if (!(weight * fits > 1e-3)) return;
  const double gain = variance / (variance + noise / (weight * fits));
  mean += gain * innovation;
  variance *= 1.0 - gain;
  anchored_ = true;
  anchor_mean_ = mean, anchor_variance_ = variance;
  anchor_pose_ = pose_, anchor_time_s_ = time_s_;
}

}  // namespace pliant::estimation::filter_internal
