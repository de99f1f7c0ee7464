// The held-out RMS error's noise floor: what white noise alone leaves in the
// windowed RMS, against closed forms.
#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "../../estimation/src/diagnosis_internal.h"

namespace pliant::estimation::diagnosis {
namespace {

// Ten segments of 20 s at 100 Hz, joint 1 only, 1 mm per rad, windows of 5
// samples (0.045 s: a sample 0.05 s after a window's first opens the next).
Problem Segments() {
  Problem problem;
  problem.rms_window_s = 0.045;
  for (int g = 0; g < 10; ++g) {
    for (int i = 0; i < 2000; ++i) {
      Sample s;
      s.group = g;
      s.state.time_s = 0.01 * i;
      s.used = {true, false};
      s.mm_per_rad = {1.0, 0.0};
      problem.samples.push_back(s);
    }
  }
  problem.groups = 10;
  return problem;
}

// A model error of 0.1 mm amplitude over a 2 s push (RMS 0.0707 mm) and white
// noise of 0.2 mm per sample: a 5-sample window keeps 0.2/√5 = 0.0894 mm of
// it. The windowed RMS is √(0.0707² + 0.0894²) = 0.114 mm; the floor is
// 0.0894 mm, within 3 %, with the error or without it.
TEST(NoiseFloor, IsWhatWhiteNoiseLeavesAfterTheWindows) {
  const Problem problem = Segments();
  std::mt19937 random(3);
  std::normal_distribution<double> noise(0.0, 0.2);
  std::vector<Eigen::Vector2d> noisy, error_only;
  for (const Sample& s : problem.samples) {
    const double error = 0.1 * std::sin(2.0 * M_PI * s.state.time_s / 2.0);
    error_only.emplace_back(error, 0.0);
    noisy.emplace_back(error + noise(random), 0.0);
  }
  const double floor = 0.2 / std::sqrt(5.0);
  EXPECT_NEAR(NoiseFloorMm(problem, noisy), floor, 0.03 * floor);
  EXPECT_NEAR(TipRmsMm(problem, noisy), std::hypot(0.1 / std::sqrt(2.0), floor), 0.03 * 0.114);
  // Without noise the floor reads what the error changes from window to
  // window (0.0157 mm per window at most here): under a tenth of the noise's,
  // under 0.5 % of it in quadrature.
  EXPECT_LT(NoiseFloorMm(problem, error_only), 0.1 * floor);
}

// Noise averaged over 3 samples (a moving mean of white noise x, σ 0.2 mm) is
// correlated within a window. A 5-sample window's mean weighs x_0 … x_6 by
// 1, 2, 3, 3, 3, 2, 1 over 15: it keeps σ²·37/225, not the σ²/3/5 = σ²·15/225
// of its per-sample variance. Neighbouring windows share x_5, x_6 (weights
// 2, 1 and 1, 2: covariance σ²·4/225), so their means differ by σ²·66/225 in
// mean square, and the floor reads σ²·(66/225)/2 = σ²·33/225: 6 % under what
// the windows keep, where the per-sample variance would be 36 % under.
TEST(NoiseFloor, CountsNoiseCorrelatedWithinAWindowAsTheWindowsKeepIt) {
  const Problem problem = Segments();
  std::mt19937 random(4);
  std::normal_distribution<double> white(0.0, 0.2);
  std::vector<double> raw(problem.samples.size() + 2);
  for (double& x : raw) x = white(random);
  std::vector<Eigen::Vector2d> residual;
  for (std::size_t i = 0; i < problem.samples.size(); ++i)
    residual.emplace_back((raw[i] + raw[i + 1] + raw[i + 2]) / 3.0, 0.0);
  const double read = 0.2 * std::sqrt(33.0 / 225.0);
  EXPECT_NEAR(NoiseFloorMm(problem, residual), read, 0.04 * read);
  EXPECT_NEAR(TipRmsMm(problem, residual), 0.2 * std::sqrt(37.0 / 225.0), 0.04 * read);
}

}  // namespace
}  // namespace pliant::estimation::diagnosis
