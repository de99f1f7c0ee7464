#include "pliant/estimation/tip_error_statistics.h"

#include <cmath>

#include <gtest/gtest.h>

#include "pliant/models/psm_kinematics.h"

namespace pliant::estimation {
namespace {

TEST(TipErrorStatistics, RmsAndMaxOfKnownDisplacements) {
  TipErrorStatistics stats;
  const Eigen::Vector3d q(0.0, 0.0, 0.1156);  // r = 0.1 m exactly
  stats.Add(q, {0.0, 0.01});                   // pitch chord 2·r·sin(0.005)
  stats.Add(q, {0.0, -0.02});
  stats.Add(q, {std::nan(""), 0.0});  // ignored
  const double a = 1000.0 * 2.0 * 0.1 * std::sin(0.005);
  const double b = 1000.0 * 2.0 * 0.1 * std::sin(0.01);
  EXPECT_EQ(stats.count(), 2u);
  EXPECT_NEAR(stats.RmsMm(), std::sqrt((a * a + b * b) / 2.0), 1e-9);
  EXPECT_NEAR(stats.MaxMm(), b, 1e-9);
}

TEST(TipErrorStatistics, EmptyIsNan) {
  EXPECT_TRUE(std::isnan(TipErrorStatistics().RmsMm()));
}

}  // namespace
}  // namespace pliant::estimation
