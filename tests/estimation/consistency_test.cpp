#include "pliant/estimation/consistency.h"

#include <cmath>

#include <boost/math/distributions/normal.hpp>
#include <gtest/gtest.h>

namespace pliant::estimation {
namespace {

TEST(Consistency, NeesOfAKnownErrorAndCovariance) {
  // P = [4 1; 1 2], det 7, P⁻¹ = [2 −1; −1 4]/7: e = (1, 2) gives (2 − 4 + 16)/7 = 2.
  Eigen::Matrix2d p;
  p << 4.0, 1.0, 1.0, 2.0;
  EXPECT_NEAR(Nees({1.0, 2.0}, p), 2.0, 1e-12);
  // Independent joints, σ = 1 and 2 mrad: (3/1)² + (−2/2)² = 10.
  const Eigen::Matrix2d diagonal = Eigen::Vector2d(1e-6, 4e-6).asDiagonal();
  EXPECT_NEAR(Nees({0.003, -0.002}, diagonal), 10.0, 1e-9);
}

TEST(Consistency, MeanMaxAndCoverageOfConstructedSamples) {
  const Eigen::Matrix2d unit = Eigen::Matrix2d::Identity();  // σ = 1 rad: NEES = e1² + e2²
  ConsistencyTally tally;
  // Inside ±z(0.975) = ±1.959964: joint 1 on 3 of 4 samples, joint 2 on 1 of 4
  // (1.96 is just beyond z).
  tally.Add({1.95, 0.0}, unit);
  tally.Add({1.97, -2.5}, unit);
  tally.Add({-1.9599, 3.0}, unit);
  tally.Add({0.0, 1.96}, unit);
  tally.Add({4.0, 4.0}, unit, /*score_coverage=*/false);  // NEES only
  EXPECT_EQ(tally.nees_count, 5);
  EXPECT_EQ(tally.coverage_count, 4);
  EXPECT_EQ(tally.covered[0], 3);
  EXPECT_EQ(tally.covered[1], 1);
  EXPECT_DOUBLE_EQ(tally.CoverageFraction(0), 0.75);
  EXPECT_DOUBLE_EQ(tally.CoverageFraction(1), 0.25);
  EXPECT_DOUBLE_EQ(tally.PooledCoverageFraction(), 0.5);
  const double sum =
      1.95 * 1.95 + (1.97 * 1.97 + 6.25) + (1.9599 * 1.9599 + 9.0) + 1.96 * 1.96 + 32.0;
  EXPECT_NEAR(tally.MeanNees(), sum / 5.0, 1e-12);
  EXPECT_NEAR(tally.max_nees, 32.0, 1e-12);
}

TEST(Consistency, CoverageUsesEachJointsOwnSigma) {
  // σ1 = 0.5, σ2 = 3 (rad): the interval is ±0.98 on joint 1, ±5.88 on joint 2.
  const Eigen::Matrix2d p = Eigen::Vector2d(0.25, 9.0).asDiagonal();
  ConsistencyTally tally;
  tally.Add({0.97, 5.87}, p);
  tally.Add({0.99, 5.89}, p);
  EXPECT_EQ(tally.covered[0], 1);
  EXPECT_EQ(tally.covered[1], 1);
}

TEST(Consistency, EmptyTallyIsNan) {
  const ConsistencyTally tally;
  EXPECT_TRUE(std::isnan(tally.MeanNees()));
  EXPECT_TRUE(std::isnan(tally.PooledCoverageFraction()));
}

TEST(Consistency, NormalQuantileIsTheTabulatedValue) {
  EXPECT_NEAR(NormalQuantile975(), 1.959963984540054, 1e-15);
}

TEST(Consistency, BandOfTheMeanOfIndependentNees) {
  // One value: χ²(2) is exponential with mean 2, quantile −2·ln(1 − p).
  const NeesBand one = MeanNeesBand95(1);
  EXPECT_NEAR(one.lower, -2.0 * std::log(0.975), 1e-12);
  EXPECT_NEAR(one.upper, -2.0 * std::log(0.025), 1e-12);
  // 200 values: χ²(400, 0.025)/200 and χ²(400, 0.975)/200 (Wilson–Hilferty agrees to 1e-4).
  const NeesBand band = MeanNeesBand95(200);
  EXPECT_NEAR(band.lower, 1.7324088268, 1e-9);
  EXPECT_NEAR(band.upper, 2.2865274098, 1e-9);
  EXPECT_TRUE(band.Contains(2.0));
  EXPECT_FALSE(band.Contains(1.70));
  EXPECT_FALSE(band.Contains(2.30));
}

}  // namespace
}  // namespace pliant::estimation
