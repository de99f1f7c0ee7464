// The free level (FilterOptions::free_level): what a settled free arm's
// effort holds beyond the learned arm torque where it stands — the bias
// table's error at that pose and the error of the torque's τ_b — learned
// online as a field over the pose, one per joint (filter_free_level.cpp;
// docs/decisions/contact-free-level.md says why).
#pragma once

#include <Eigen/Core>

#include "pliant/estimation/filter_options.h"

namespace pliant::estimation::filter_internal {

struct FreeLevel {
  bool on = false;
  double mean = 0.0, variance = 0.0;  // at this row's pose, N·m and N·m²
  double still = 1.0;                 // how still the free arm stands, in [0, 1]

  void Start(const FilterOptions& o, double equilibrium_nm2);
  // Carries the level to this row: `pose` is (z1, z2, depth) — each joint's
  // free-arm angle z = q_enc − s·K(L)·r (rad) and the insertion (m) — and
  // `equilibrium_nm2` the field's variance where nothing was learned
  // (σ_rest² + the torque's τ_b variance).
  void Predict(const Eigen::Vector3d& pose, double dt_s, double still_share,
               double equilibrium_nm2);
  // The torque and variance the level adds to the free arm's: the level is a
  // settled arm's (it holds the static friction the motor stopped with, which
  // a moving arm's Coulomb friction replaces), so a moving arm has the field's
  // prior instead.
  double Torque() const { return still * mean; }
  double Variance(double equilibrium_nm2) const {
    return still * still * variance + (1.0 - still * still) * equilibrium_nm2;
  }
  // A lesson: a batch's mean residual without the level (N·m) at its mean
  // pose, with the weight 1 − its largest contact probability.
  void Teach(double residual_nm, const Eigen::Vector3d& pose, double weight,
             double equilibrium_nm2);

 private:
  double Correlation(const Eigen::Vector3d& a, const Eigen::Vector3d& b) const;
  Eigen::Vector3d pose_ = Eigen::Vector3d::Zero(), anchor_pose_ = Eigen::Vector3d::Zero();
  Eigen::Vector3d inverse_length_ = Eigen::Vector3d::Ones();
  bool anchored_ = false;
  double time_s_ = 0.0, anchor_time_s_ = 0.0, anchor_mean_ = 0.0, anchor_variance_ = 0.0;
  double drift2_ = 0.0, rest2_ = 0.0, noise2_ = 0.0, limit2_ = 0.0;
};

}  // namespace pliant::estimation::filter_internal
