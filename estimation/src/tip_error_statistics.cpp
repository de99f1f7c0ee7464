#include "pliant/estimation/tip_error_statistics.h"

#include <algorithm>
#include <cmath>

#include "pliant/models/psm_kinematics.h"

namespace pliant::estimation {

void TipErrorStatistics::Add(const Eigen::Vector3d& q, const Eigen::Vector2d& reference_rad) {
  if (!q.allFinite() || !reference_rad.allFinite()) return;
  const Eigen::Vector2d error = reference_rad - q.head<2>();
  const double mm = models::TipErrorMm(q, error[0], error[1]);
  ++count_;
  sum_squares_mm2_ += mm * mm;
  max_mm_ = std::max(max_mm_, mm);
}

double TipErrorStatistics::RmsMm() const {
  return count_ ? std::sqrt(sum_squares_mm2_ / double(count_))
                : std::numeric_limits<double>::quiet_NaN();
}

}  // namespace pliant::estimation
