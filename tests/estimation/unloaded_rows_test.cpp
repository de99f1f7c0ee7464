#include "pliant/estimation/unloaded_rows.h"

#include <cmath>
#include <random>

#include <gtest/gtest.h>

namespace pliant::estimation {
namespace {

// A synthetic log's loads: a push (rows 0–49, 0.2 → 1.2 N·m), 30 untouched
// rows at a bias error of 0.05 N·m with ±0.004 N·m of deterministic noise,
// then another push.
std::vector<double> PushRestPush() {
  std::vector<double> load;
  for (int r = 0; r < 50; ++r) load.push_back(0.2 + 0.02 * r);
  for (int r = 0; r < 30; ++r) load.push_back(0.05 + 0.004 * std::sin(1.7 * r));
  for (int r = 0; r < 40; ++r) load.push_back(-0.1 - 0.03 * r);
  return load;
}

TEST(UnloadedRows, FindsTheUntouchedRowsAndTheirOffset) {
  const auto load = PushRestPush();
  const auto run = FindUnloadedRun(load, 0.01, 10);
  EXPECT_EQ(run.first_row, 50u);
  EXPECT_EQ(run.rows, 30u);
  const auto tare = TareOn(load, run, 0.01);
  EXPECT_EQ(tare.rows, 30u);
  EXPECT_NEAR(tare.offset_nm, 0.05, 0.002);
  EXPECT_TRUE(tare.disagrees);  // 0.05 N·m is beyond 2σ of a 0.01 N·m bias
  EXPECT_FALSE(TareOn(load, run, 0.05).disagrees);
}

TEST(UnloadedRows, NoSteadyRunIsNoTare) {
  std::vector<double> ramp;
  for (int r = 0; r < 100; ++r) ramp.push_back(0.05 * r);
  EXPECT_EQ(FindUnloadedRun(ramp, 0.01, 10).rows, 0u);
}

TEST(UnloadedRows, AMissingLoadEndsARun) {
  auto load = PushRestPush();
  load[65] = std::nan("");
  const auto run = FindUnloadedRun(load, 0.01, 10);
  EXPECT_EQ(run.first_row, 50u);  // rows 50–64; 66–79 is one row shorter
  EXPECT_EQ(run.rows, 15u);
}


// Fraction of 400 AR(1) series (n rows, lag-one correlation rho, true mean 0)
// whose tare lies within 1.96 of its stated sd of the truth.
double TareCoverage(double rho, std::size_t n) {
  std::mt19937 rng(20261126);
  std::normal_distribution<double> innovation(0.0, 0.003);
  int covered = 0;
  const int series = 400;
  for (int k = 0; k < series; ++k) {
    std::vector<double> load(n);
    double x = innovation(rng) / std::sqrt(1.0 - rho * rho);  // stationary start
    for (auto& v : load) v = x = rho * x + innovation(rng);
    const auto tare = TareOn(load, {0, n}, 0.0);
    covered += std::abs(tare.offset_nm) <= 1.96 * tare.sd_nm;
  }
  return double(covered) / series;
}

// A steady load whose rows share their errors (an arm that settles, a sweep's
// pose-to-pose bias error): sd/√n would cover the mean on about 36 % of such
// series at a lag-one correlation of 0.9 (Monte Carlo of the same model); the
// batch means bring it to about 89 %, and leave independent rows at 95 %.
TEST(UnloadedRows, TheTareSigmaCoversTheMeanWhenRowsShareTheirErrors) {
  EXPECT_GE(TareCoverage(0.9, 1000), 0.85);
  const double white = TareCoverage(0.0, 1000);
  EXPECT_GE(white, 0.92);
  EXPECT_LE(white, 0.98);
}

}  // namespace
}  // namespace pliant::estimation
