// The effort's white noise from a log's own samples (effort_noise.h), and how
// a log's filter options take it (EffortNoiseForLog).
#include "pliant/estimation/effort_noise.h"

#include <cmath>
#include <random>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "pliant/estimation/filter_log.h"

namespace pliant::estimation {
namespace {

// White noise of σ on a smooth load (a 1 N·m push of 1 s at 1.5 kHz) and on a
// step at every 400th row: the median of |Δ²τ| / (0.6745·√6) is σ. Its spread
// over n triples is about 1.1·σ/√n (the median's of a half-normal), 1.7 % at
// n = 4,000: 6 % is over 3 of them.
TEST(EffortNoise, TheMedianSecondDifferenceGivesTheWhiteNoise) {
  for (const double sd : {0.003, 0.01, 0.03}) {
    std::mt19937 rng(7);
    std::normal_distribution<double> noise(0.0, sd);
    std::vector<double> effort;
    for (int k = 0; k < 4000; ++k) {
      const double t = k / 1500.0;
      const double load = std::sin(M_PI * t) * std::sin(M_PI * t) + 0.2 * ((k / 400) % 2);
      effort.push_back(load + noise(rng));
    }
    EXPECT_NEAR(EffortNoiseFromSamples(effort), sd, 0.06 * sd) << "sd " << sd;
  }
}

// A quantised effort at rest: most second differences are 0; the quantum
// (the smallest step between samples) over √12 is what is left.
TEST(EffortNoise, AQuantisedEffortAtRestGivesItsQuantum) {
  const double quantum = 0.002;
  std::vector<double> effort(200, 0.1);
  for (int k = 0; k < 200; k += 10) effort[k] += quantum;
  EXPECT_NEAR(EffortNoiseFromSamples(effort), quantum / std::sqrt(12.0), 1e-15);
}

TEST(EffortNoise, TooFewSamplesSayNothing) {
  EXPECT_TRUE(std::isnan(EffortNoiseFromSamples(std::vector<double>(kMinNoiseTriples + 1, 0.0))));
  std::vector<double> gaps(400, std::nan(""));
  EXPECT_TRUE(std::isnan(EffortNoiseFromSamples(gaps)));
}

std::vector<double> Noisy(double sd, int seed) {
  std::mt19937 rng(seed);
  std::normal_distribution<double> noise(0.0, sd);
  std::vector<double> effort(3000);
  for (auto& e : effort) e = 0.3 + noise(rng);
  return effort;
}

// With effort_noise_from_log the option is raised to the noisier joint's
// estimate, never lowered; it is left alone on a quasi-static log or for a
// joint the log does not record. Without, the note alone says it.
TEST(EffortNoiseForLog, RaisesTheAssumedNoiseToTheLogsOwnOnly) {
  const std::vector<double> quiet[2] = {Noisy(0.003, 1), Noisy(0.004, 2)};
  const std::vector<double> loud[2] = {Noisy(0.012, 3), Noisy(0.03, 4)};
  std::vector<std::string> notes, advice;
  FilterOptions o;
  o.effort_noise_from_log = true;
  EXPECT_EQ(EffortNoiseForLog(o, quiet, &notes, &advice).effort_noise_nm, 0.01);
  EXPECT_TRUE(notes.empty());
  EXPECT_NEAR(EffortNoiseForLog(o, loud, &notes, &advice).effort_noise_nm, 0.03, 0.002);
  ASSERT_EQ(notes.size(), 1u);
  EXPECT_NE(notes[0].find("hold 0.0"), std::string::npos) << notes[0];
  EXPECT_NE(notes[0].find(": used"), std::string::npos) << notes[0];
  FilterOptions joint1_only = o;
  joint1_only.joint_recorded[1] = false;
  EXPECT_NEAR(EffortNoiseForLog(joint1_only, loud, &notes, &advice).effort_noise_nm, 0.012, 0.001);
  FilterOptions poses = o;
  poses.quasi_static = true;
  EXPECT_EQ(EffortNoiseForLog(poses, loud, &notes, &advice).effort_noise_nm, 0.01);
  notes.clear();
  EXPECT_EQ(EffortNoiseForLog(FilterOptions{}, loud, &notes, &advice).effort_noise_nm, 0.01);
  EXPECT_TRUE(notes.empty());  // (nothing the output's metadata need say)
  ASSERT_EQ(advice.size(), 1u);
  EXPECT_NE(advice[0].find("--effort-noise-from-log uses it"), std::string::npos) << advice[0];
}

}  // namespace
}  // namespace pliant::estimation
