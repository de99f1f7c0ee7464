// The checkpointed smoother (estimation/src/smoothed_pass.h) against
// FilterSmoother: the same smoothed estimates to the bit, over logs that
// span many blocks (and thin the checkpoints), with motor inertia held
// samples, a time gap (re-initialisation), an encoder jump, a release and
// re-hold elsewhere (the load restarts) and NaN depths.
#include <cmath>
#include <random>
#include <vector>

#include <gtest/gtest.h>

#include "../../estimation/src/scratch_file.h"
#include "../../estimation/src/smoothed_pass.h"
#include "../support/paper_parameters.h"
#include "pliant/estimation/filter_smoother.h"

namespace pliant::estimation {
namespace {

constexpr double kPi = 3.14159265358979323846;

// Free motion (two sines); a held tip pushed at 0.15 m, then held again at
// 0.12 m without a free sample between (a release: the load restarts); free;
// a 2 s gap in time, an encoder jump of 0.3 rad and rows without a depth on
// the way. Efforts carry N(0, 0.02²) noise.
std::vector<FilterSample> EventfulLog(std::size_t n) {
  std::mt19937_64 rng(5);
  std::normal_distribution<double> noise(0.0, 0.02);
  std::vector<FilterSample> samples;
  const double dt = 1.0 / 1500.0;
  double time = 0.0;
  for (std::size_t k = 0; k < n; ++k) {
    const double phase = double(k) / double(n);
    FilterSample s;
    time += k == n / 2 ? 2.0 : dt;  // the gap
    s.time_s = time;
    s.tip_fixed = (phase > 0.2 && phase < 0.4) || (phase > 0.45 && phase < 0.6);
    s.insertion_depth_m = phase < 0.5 ? 0.15 : 0.12;  // re-held at 0.12 m
    if (k % 97 == 13) s.insertion_depth_m = FilterSample::kMissing;
    const double load = s.tip_fixed ? 0.4 * std::sin(2.0 * kPi * 0.7 * time) : 0.0;
    for (int j = 0; j < 2; ++j) {
      const double motion = s.tip_fixed ? 0.0 : 0.2 * std::sin(2.0 * kPi * (0.5 + j) * time);
      s.encoder_rad[j] = motion + 0.004 * load + (phase > 0.7 ? 0.3 : 0.0);  // the jump
      s.effort_nm[j] = load + noise(rng);
    }
    samples.push_back(s);
  }
  return samples;
}

void ExpectSameEstimate(const FilterEstimate& a, const FilterEstimate& b, std::size_t k) {
  ASSERT_EQ(a.corrected_rad, b.corrected_rad) << "sample " << k;
  ASSERT_EQ(a.covariance_rad2, b.covariance_rad2) << "sample " << k;
  ASSERT_EQ(a.filtered_rad, b.filtered_rad) << "sample " << k;
  ASSERT_EQ(a.external_torque_nm, b.external_torque_nm) << "sample " << k;
  ASSERT_EQ(a.backlash_offset_rad, b.backlash_offset_rad) << "sample " << k;
  ASSERT_EQ(a.compliance_scale, b.compliance_scale) << "sample " << k;
  ASSERT_EQ(a.effort_offset_nm, b.effort_offset_nm) << "sample " << k;
  // NaN-safe exact comparison of the scalars.
  ASSERT_EQ(std::isnan(a.tip_correction_mm), std::isnan(b.tip_correction_mm));
  if (!std::isnan(a.tip_correction_mm)) {
    ASSERT_EQ(a.tip_correction_mm, b.tip_correction_mm) << "sample " << k;
    ASSERT_EQ(a.tip_correction_sd_mm, b.tip_correction_sd_mm) << "sample " << k;
  }
  ASSERT_EQ(a.nis, b.nis) << "sample " << k;
  ASSERT_EQ(a.nis_dof, b.nis_dof) << "sample " << k;
  ASSERT_EQ(a.flags, b.flags) << "sample " << k;
}

struct Compared {
  std::size_t blocks_taken = 0;
  std::uint32_t flags_seen = 0;
  double largest_smoothing_rad = 0.0;  // |smoothed − filtered| of q1
};

// Runs both smoothers on `samples` and asserts every estimate is the same.
Compared CompareSmoothers(const FilterOptions& options, const std::vector<FilterSample>& samples,
                          std::size_t block_records) {
  const auto p = models::testing::PaperParameters();
  FilterSmoother whole(p, options);
  CheckpointedSmoother checkpointed(p, options, block_records);
  for (const FilterSample& s : samples) {
    const FilterEstimate a = whole.Add(s), b = checkpointed.Add(s);
    ExpectSameEstimate(a, b, 0);
  }
  std::vector<FilterEstimate> filtered;
  for (std::size_t k = 0; k < whole.size(); ++k) filtered.push_back(whole.Estimate(k));
  whole.Smooth();
  Compared result;
  std::vector<bool> taken(samples.size(), false);
  const auto read = [&](std::size_t first, std::size_t count, std::vector<FilterSample>* out) {
    ASSERT_LE(first + count, samples.size());
    out->assign(samples.begin() + std::ptrdiff_t(first),
                samples.begin() + std::ptrdiff_t(first + count));
  };
  const auto take = [&](std::size_t first, const std::vector<FilterEstimate>& estimates) {
    ++result.blocks_taken;
    for (std::size_t k = 0; k < estimates.size(); ++k) {
      ASSERT_FALSE(taken[first + k]);
      taken[first + k] = true;
      ExpectSameEstimate(whole.Estimate(first + k), estimates[k], first + k);
      result.flags_seen |= estimates[k].flags;
    }
  };
  checkpointed.Smooth(read, take);
  EXPECT_EQ(std::count(taken.begin(), taken.end(), true), std::ptrdiff_t(samples.size()));
  for (std::size_t k = 0; k < filtered.size(); ++k) {
    result.largest_smoothing_rad =
        std::max(result.largest_smoothing_rad,
                 std::abs(whole.Estimate(k).corrected_rad[0] - filtered[k].corrected_rad[0]));
  }
  return result;
}

FilterOptions WithInertia() {
  FilterOptions o;
  o.motor_inertia_kg_m2 = 0.08;  // the simulator's arm
  o.align_inertial_torque = true;
  return o;
}

TEST(CheckpointedSmoother, MatchesFilterSmootherToTheBitWithHeldSamples) {
  const auto p = models::testing::PaperParameters();
  ASSERT_GT(ComplianceFilter(p, WithInertia()).alignment_steps(), 10);
  const auto samples = EventfulLog(6000);
  const Compared c = CompareSmoothers(WithInertia(), samples, 7);
  // 6000 records from blocks of 7: the checkpoints were thinned to blocks of
  // 7·2ⁿ; many blocks all the same.
  EXPECT_GT(c.blocks_taken, 40u);
  EXPECT_NE(c.flags_seen & kFlagReinitialised, 0u);
  EXPECT_GT(c.largest_smoothing_rad, 1e-4);  // the smoother did move the estimates
}

TEST(CheckpointedSmoother, MatchesFilterSmootherWithoutInertiaAndAtEveryBlockLength) {
  const auto samples = EventfulLog(700);
  for (std::size_t block : {1u, 2u, 3u, 64u, 699u, 700u, 701u, 5000u}) {
    SCOPED_TRACE(block);
    const Compared c = CompareSmoothers(FilterOptions{}, samples, block);
    EXPECT_EQ(c.blocks_taken == 1, block >= 700);
  }
}

// Logs shorter than the alignment: every record comes from the held samples.
TEST(CheckpointedSmoother, MatchesFilterSmootherOnLogsShorterThanTheAlignment) {
  const auto samples = EventfulLog(600);
  for (std::size_t n : {1u, 2u, 5u, 20u}) {
    SCOPED_TRACE(n);
    const std::vector<FilterSample> head(samples.begin(), samples.begin() + std::ptrdiff_t(n));
    CompareSmoothers(WithInertia(), head, 3);
  }
}

TEST(CheckpointedSmoother, ThinsItsCheckpointsAsTheLogGrows) {
  const auto p = models::testing::PaperParameters();
  CheckpointedSmoother smoother(p, FilterOptions{}, 16);
  const auto samples = EventfulLog(20000);
  for (const auto& s : samples) smoother.Add(s);
  // 64 checkpoints of blocks of 16 are 1024 records: then 33 of 32, … up
  // to blocks of 512 (64 of them would be 32,768 records).
  EXPECT_EQ(smoother.block_records(), 512u);
  EXPECT_LE(smoother.checkpoints(),
            std::max(CheckpointedSmoother::kMinCheckpoints,
                     smoother.block_records() / CheckpointedSmoother::kRecordsPerCheckpoint));
  EXPECT_GE(smoother.checkpoints() * smoother.block_records(), samples.size());
}

TEST(ScratchFile, ReadsBackWhatWasAppendedAndWritten) {
  ScratchFile file("test");
  std::vector<double> values(300000);
  for (std::size_t i = 0; i < values.size(); ++i) values[i] = 0.5 * double(i);
  file.Append(values.data(), 7);
  file.Append(values.data() + 7, values.size() - 7);  // past the buffer
  const double patch[2] = {-1.0, -2.0};
  file.Write(100, patch, 2);
  std::vector<double> back(values.size());
  file.Read(0, back.size(), back.data());
  values[100] = -1.0, values[101] = -2.0;
  EXPECT_EQ(back, values);
  double beyond = 0.0;
  EXPECT_THROW(file.Read(values.size(), 1, &beyond), std::runtime_error);
}

}  // namespace
}  // namespace pliant::estimation
