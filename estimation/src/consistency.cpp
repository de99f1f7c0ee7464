#include "pliant/estimation/consistency.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include <Eigen/Cholesky>
#include <boost/math/distributions/chi_squared.hpp>
#include <boost/math/distributions/normal.hpp>

namespace pliant::estimation {

double NormalQuantile975() {
  static const double z = boost::math::quantile(boost::math::normal(), 0.975);
  return z;
}

double Nees(const Eigen::Vector2d& error_rad, const Eigen::Matrix2d& covariance_rad2) {
  return error_rad.dot(covariance_rad2.ldlt().solve(error_rad));
}

void ConsistencyTally::Add(const Eigen::Vector2d& error_rad,
                           const Eigen::Matrix2d& covariance_rad2, bool score_coverage) {
  const double nees = Nees(error_rad, covariance_rad2);
  nees_sum += nees;
  max_nees = std::max(max_nees, nees);
  ++nees_count;
  if (!score_coverage) return;
  ++coverage_count;
  const double z = NormalQuantile975();
  for (int j = 0; j < 2; ++j) {
    covered[j] += std::abs(error_rad[j]) <= z * std::sqrt(covariance_rad2(j, j));
  }
}

double ConsistencyTally::MeanNees() const {
  return nees_count ? nees_sum / double(nees_count) : std::numeric_limits<double>::quiet_NaN();
}

double ConsistencyTally::CoverageFraction(int joint) const {
  return double(covered[joint]) / double(coverage_count);
}

double ConsistencyTally::PooledCoverageFraction() const {
  return double(covered[0] + covered[1]) / double(2 * coverage_count);
}

NeesBand MeanNeesBand95(long independent_values) {
  const double n = double(independent_values);
  const boost::math::chi_squared chi(2.0 * n);
  return {boost::math::quantile(chi, 0.025) / n, boost::math::quantile(chi, 0.975) / n};
}

}  // namespace pliant::estimation
