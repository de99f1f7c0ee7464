#pragma once
// Is a claimed 2×2 joint covariance honest? Tallies corrected-joint errors
// e = q̂ − q_true (rad) against the covariance P (rad²) an estimator gives with
// them: the NEES e·P⁻¹·e (χ² with 2 dof when P is right) and the 95 % interval
// coverage |e_j| ≤ z(0.975)·σ_j of each joint. Used by the Monte Carlo trials
// (experiments/src/trial.cpp) and bench/filter_consistency_bench.

#include <Eigen/Core>

namespace pliant::estimation {

/// Two-sided 95 % normal quantile z(0.975), from Boost.Math (computed once).
double NormalQuantile975();

/// Normalised estimation error squared e·P⁻¹·e of a 2-D error and its covariance.
double Nees(const Eigen::Vector2d& error_rad, const Eigen::Matrix2d& covariance_rad2);

struct ConsistencyTally {
  double nees_sum = 0.0;
  double max_nees = 0.0;
  long nees_count = 0;
  long covered[2] = {0, 0};  ///< per joint: samples with |e_j| ≤ z(0.975)·σ_j
  long coverage_count = 0;   ///< samples scored for coverage

  /// Adds one sample's NEES, and its coverage unless `score_coverage` is false.
  void Add(const Eigen::Vector2d& error_rad, const Eigen::Matrix2d& covariance_rad2,
           bool score_coverage = true);
  /// NaN when nothing was added.
  double MeanNees() const;
  /// Fraction of the scored samples inside the 95 % interval on joint `joint`
  /// (0 or 1); NaN when none was scored.
  double CoverageFraction(int joint) const;
  /// The same over both joints together.
  double PooledCoverageFraction() const;
};

/// Where the mean of n independent 2-dof NEES values lies with 95 %
/// probability when the covariance is right: [χ²(2n, 0.025), χ²(2n, 0.975)] / n.
struct NeesBand {
  double lower = 0.0, upper = 0.0;
  bool Contains(double mean_nees) const { return mean_nees >= lower && mean_nees <= upper; }
};
NeesBand MeanNeesBand95(long independent_values);

}  // namespace pliant::estimation
