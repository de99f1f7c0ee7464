// The residual tests of the diagnosis against closed forms and known
// distributions: Ljung–Box, Jarque–Bera, Holm, the AR(1) effective size.
#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "../../estimation/src/diagnosis_internal.h"

namespace pliant::estimation::diagnosis {
namespace {

std::vector<double> Ar1(double rho, std::size_t n, unsigned seed) {
  std::mt19937 rng(seed);
  std::normal_distribution<double> noise(0.0, 1.0);
  std::vector<double> x(n);
  double state = 0.0;
  for (double& v : x) v = state = rho * state + noise(rng);
  return x;
}

TEST(DiagnosisStatistics, LjungBoxRejectsOnlyCorrelatedSeriesAtItsLevel) {
  int rejected_white = 0;
  for (unsigned seed = 0; seed < 200; ++seed) rejected_white += LjungBox(Ar1(0.0, 2000, seed), 20).p_value < 0.05;
  // 5 % of 200 white series: binomial sd 3.1, so 10 ± 9 covers 99.5 %.
  EXPECT_NEAR(rejected_white, 10, 9);
  EXPECT_LT(LjungBox(Ar1(0.3, 2000, 1), 20).p_value, 1e-10);
}

TEST(DiagnosisStatistics, JarqueBeraMatchesItsClosedFormAndSeesAUniform) {
  // {−1, +1} repeated: skew 0, kurtosis 1 → JB = n/6·(0 + 4/4) = n/6.
  std::vector<double> two_point(600);
  for (std::size_t i = 0; i < two_point.size(); ++i) two_point[i] = i % 2 ? 1.0 : -1.0;
  EXPECT_NEAR(JarqueBera(two_point).statistic, 100.0, 1e-9);
  EXPECT_GT(JarqueBera(Ar1(0.0, 5000, 3)).p_value, 0.001);
  std::mt19937 rng(4);
  std::uniform_real_distribution<double> uniform(-1.0, 1.0);
  std::vector<double> flat(5000);
  for (double& v : flat) v = uniform(rng);
  EXPECT_LT(JarqueBera(flat).p_value, 1e-10);  // excess kurtosis −1.2
}

TEST(DiagnosisStatistics, HolmAdjustsStepDown) {
  std::vector<double> p = {0.01, 0.04, 0.03, 0.5};
  HolmAdjust(p);
  // Sorted 0.01, 0.03, 0.04, 0.5 times 4, 3, 2, 1, made monotone.
  EXPECT_DOUBLE_EQ(p[0], 0.04);
  EXPECT_DOUBLE_EQ(p[2], 0.09);
  EXPECT_DOUBLE_EQ(p[1], 0.09);
  EXPECT_DOUBLE_EQ(p[3], 0.5);
}

TEST(DiagnosisStatistics, EffectiveSizeOfAnAr1SeriesIsItsClosedForm) {
  const auto x = Ar1(0.8, 200000, 5);
  const std::vector<int> run(x.size(), 0);
  // (1 − ρ)/(1 + ρ) = 0.2/1.8.
  EXPECT_NEAR(EffectiveSizeFactor(x, run), 0.2 / 1.8, 0.005);
  const auto band = ChiSquaredMeanBand(2000.0);
  EXPECT_NEAR(band[0], 1.0 - 1.96 * std::sqrt(2.0 / 2000.0), 0.003);
  EXPECT_NEAR(band[1], 1.0 + 1.96 * std::sqrt(2.0 / 2000.0), 0.003);
}

}  // namespace
}  // namespace pliant::estimation::diagnosis
