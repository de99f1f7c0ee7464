#pragma once
// Running accuracy of joint estimates against a reference (ground truth or an
// optical tracker), as tip displacement in mm through the PSM kinematics.

#include <cstddef>
#include <limits>

#include <Eigen/Core>

namespace pliant::estimation {

class TipErrorStatistics {
 public:
  /// q = (q1, q2, q3) as estimated; reference = (q1, q2) the tip really had.
  /// Samples with a non-finite value are ignored.
  void Add(const Eigen::Vector3d& q, const Eigen::Vector2d& reference_rad);

  std::size_t count() const { return count_; }
  double RmsMm() const;
  double MaxMm() const { return count_ ? max_mm_ : std::numeric_limits<double>::quiet_NaN(); }

 private:
  std::size_t count_ = 0;
  double sum_squares_mm2_ = 0.0;
  double max_mm_ = 0.0;
};

}  // namespace pliant::estimation
