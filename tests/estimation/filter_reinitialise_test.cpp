// Never diverge (filter.h, kFlagReinitialised): a pose change between two
// rows, a time gap, a log that starts loaded and a stretch of missing samples
// each bring the corrected angle back within 3 of its stated σ within a
// bounded number of rows, and keep it there.
#include <cmath>
#include <random>
#include <vector>

#include <gtest/gtest.h>

#include "../support/paper_parameters.h"
#include "pliant/estimation/filter.h"
#include "pliant/models/effects/backlash_hysteresis.h"

namespace pliant::estimation {
namespace {

constexpr double kRate = 1500.0;
constexpr int kBoundRows = 5;  // rows after an event before the estimate is honest again

// A free tip moving at constant rate, no load: encoder = tip + noise (the
// shaft in the middle of its clearance), effort = tau0 + noise.
struct Row {
  FilterSample sample;
  Eigen::Vector2d truth;
};

std::vector<Row> FreeMotion(int rows, double rate_rad_s, unsigned seed) {
  const auto p = models::testing::PaperParameters();
  const FilterOptions o;
  std::mt19937_64 rng(seed);
  std::normal_distribution<double> normal(0.0, 1.0);
  std::vector<Row> out;
  for (int k = 0; k < rows; ++k) {
    Row r;
    r.truth << 0.1 + rate_rad_s * k / kRate, -0.2 - 0.5 * rate_rad_s * k / kRate;
    r.sample.time_s = k / kRate;
    for (int j = 0; j < 2; ++j) {
      r.sample.encoder_rad[j] = r.truth[j] + o.encoder_noise_rad * normal(rng);
      r.sample.effort_nm[j] = models::BiasTorqueAt(p.joints[j], r.sample.encoder_rad[j], 0.15) +
                              o.effort_noise_nm * normal(rng);
    }
    out.push_back(r);
  }
  return out;
}

// The first row from which every row's corrected angle lies within 3σ of the
// truth on both joints (rows.size() when none), and the rows flagged.
struct Recovery {
  std::size_t honest_from = 0;
  int reinitialised = 0;
};

Recovery RunFilter(const std::vector<Row>& rows, std::size_t event) {
  ComplianceFilter filter(models::testing::PaperParameters());
  Recovery r;
  r.honest_from = rows.size();
  bool honest_run = false;
  for (std::size_t k = 0; k < rows.size(); ++k) {
    const FilterEstimate e = filter.Step(rows[k].sample);
    r.reinitialised += (e.flags & kFlagReinitialised) != 0;
    bool honest = true;
    for (int j = 0; j < 2; ++j) {
      const double sd = std::sqrt(e.covariance_rad2(j, j));
      honest = honest && std::abs(e.corrected_rad[j] - rows[k].truth[j]) <= 3.0 * sd + 1e-12;
    }
    if (k < event) continue;
    if (honest && !honest_run) r.honest_from = k;
    if (!honest) r.honest_from = rows.size();
    honest_run = honest;
  }
  return r;
}

TEST(FilterNeverDiverges, APoseChangeBetweenRowsRestartsTheTipAtTheEncoder) {
  // One row per pose: the arm steps 0.087 rad (5°) between consecutive rows,
  // 40 times, time stamped at the control rate.
  auto rows = FreeMotion(300, 0.0, 1);
  const std::size_t event = 100;
  for (std::size_t k = event; k < rows.size(); ++k) {
    const double step = 0.087 * double(std::min<std::size_t>(k - event + 1, 40));
    rows[k].truth[0] += step;
    rows[k].sample.encoder_rad[0] += step;
  }
  const Recovery r = RunFilter(rows, event);
  EXPECT_LE(r.honest_from, event + kBoundRows);
  EXPECT_EQ(r.reinitialised, 40);  // each step, and only those
}

TEST(FilterNeverDiverges, ATimeGapWithAnUnseenMoveIsBridged) {
  // 2 s missing from the log while the arm moved 0.3 rad on joint 1.
  auto rows = FreeMotion(600, 0.05, 2);
  const std::size_t event = 300;
  for (std::size_t k = event; k < rows.size(); ++k) {
    rows[k].sample.time_s += 2.0;
    rows[k].truth[0] += 0.3;
    rows[k].sample.encoder_rad[0] += 0.3;
  }
  const Recovery r = RunFilter(rows, event);
  EXPECT_LE(r.honest_from, event + kBoundRows);
  EXPECT_EQ(r.reinitialised, 1);
}

TEST(FilterNeverDiverges, MissingSamplesWhileTheArmMovesFastAreBridged) {
  // 150 rows (0.1 s) without encoders or efforts while joint 1 moves at 1 rad/s.
  auto rows = FreeMotion(600, 1.0, 3);
  const std::size_t event = 350;
  for (std::size_t k = 200; k < event; ++k) {
    rows[k].sample.encoder_rad.setConstant(FilterSample::kMissing);
    rows[k].sample.effort_nm.setConstant(FilterSample::kMissing);
  }
  const Recovery r = RunFilter(rows, event);
  EXPECT_LE(r.honest_from, event + kBoundRows);
  EXPECT_GE(r.reinitialised, 1);
}

// The tip held at `truth` with `start_load` (N·m) released over 1 s, the
// shafts starting on their walls; rows time stamped from `t0_s`.
std::vector<Row> HeldAndReleased(int count, const Eigen::Vector2d& truth,
                                 const Eigen::Vector2d& start_load, double t0_s, unsigned seed) {
  const auto p = models::testing::PaperParameters();
  const FilterOptions o;
  std::mt19937_64 rng(seed);
  std::normal_distribution<double> normal(0.0, 1.0);
  std::vector<Row> rows;
  Eigen::Vector2d backlash(p.joints[0].backlash_rad, -p.joints[1].backlash_rad);
  for (int k = 0; k < count; ++k) {
    Row r;
    r.truth = truth;
    r.sample.time_s = t0_s + k / kRate;
    r.sample.tip_fixed = true;
    const Eigen::Vector2d load = start_load * std::max(0.0, 1.0 - k / kRate);
    for (int j = 0; j < 2; ++j) {
      const auto& jp = p.joints[j];
      backlash[j] = models::BacklashHysteresisStep(backlash[j], load[j], jp.backlash_rad,
                                                   jp.deadzone_width_nm);
      r.sample.encoder_rad[j] = r.truth[j] + backlash[j] + models::ComplianceAt(jp, 0.15) * load[j] +
                                o.encoder_noise_rad * normal(rng);
      r.sample.effort_nm[j] = models::BiasTorqueAt(jp, r.sample.encoder_rad[j], 0.15) + load[j] +
                              o.effort_noise_nm * normal(rng);
    }
    rows.push_back(r);
  }
  return rows;
}

TEST(FilterNeverDiverges, ALogThatStartsLoadedIsHonestWithinTheBound) {
  // The tip held from the first row with 0.8 N·m on joint 1 and −0.5 on joint 2.
  const auto rows = HeldAndReleased(3000, {0.1, -0.2}, {0.8, -0.5}, 0.0, 4);
  const Recovery r = RunFilter(rows, 0);
  EXPECT_LE(r.honest_from, std::size_t(kBoundRows));
}

// A calibration log's free sweep ends at one pose and its clamp begins at
// another: the held tip is somewhere new, not where the free tip was. Kept
// where it was, joint 2 stayed 0.8 rad off on a foreign simulator's log, its
// encoder rejected on every held row.
TEST(FilterNeverDiverges, AHoldThatBeginsAPoseAwayStartsAtTheEncoder) {
  for (const double gap_s : {2.0, 0.0}) {
    auto rows = FreeMotion(300, 0.0, 5);
    const double t0 = rows.back().sample.time_s + 1.0 / kRate + gap_s;
    const auto held = HeldAndReleased(1500, {0.1, 0.6}, {0.6, -0.7}, t0, 6);
    rows.insert(rows.end(), held.begin(), held.end());
    const Recovery r = RunFilter(rows, 300);
    EXPECT_LE(r.honest_from, std::size_t(300 + kBoundRows)) << "gap " << gap_s << " s";
    EXPECT_EQ(r.reinitialised, 1) << "gap " << gap_s << " s";
  }
}

// Released and held again at another depth, after a transit the log does
// not show: whether the shaft kept its wall is unknown. An instrument whose
// clearance has no memory sits centred when unloaded; kept on its last wall
// with the doubt it had, joint 2 was 7 mrad off at 3.5σ on every row.
TEST(FilterNeverDiverges, AHoldAtAnotherDepthDoubtsTheWall) {
  const auto p = models::testing::PaperParameters();
  const FilterOptions o;
  std::mt19937_64 rng(8);
  std::normal_distribution<double> normal(0.0, 1.0);
  std::vector<Row> rows;
  const Eigen::Vector2d truth(0.1, -0.2);
  for (int k = 0; k < 3000; ++k) {
    Row r;
    r.truth = truth;
    r.sample.time_s = k / kRate;
    r.sample.tip_fixed = true;
    const bool first = k < 1500;
    r.sample.insertion_depth_m = first ? 0.12 : 0.16;
    // First hold: joint 2 pushed to −0.7 N·m and back, its shaft left on the
    // −δ wall; second hold: unloaded, the shaft centred.
    const double load2 = first ? -0.7 * std::sin(M_PI * k / 1500.0) : 0.0;
    const double wall2 = first && k > 100 ? -p.joints[1].backlash_rad : 0.0;
    const Eigen::Vector2d deflection(
        0.0, wall2 + models::ComplianceAt(p.joints[1], r.sample.insertion_depth_m) * load2);
    for (int j = 0; j < 2; ++j) {
      r.sample.encoder_rad[j] = truth[j] + deflection[j] + o.encoder_noise_rad * normal(rng);
      r.sample.effort_nm[j] =
          models::BiasTorqueAt(p.joints[j], r.sample.encoder_rad[j], r.sample.insertion_depth_m) +
          (j == 1 ? load2 : 0.0) + o.effort_noise_nm * normal(rng);
    }
    rows.push_back(r);
  }
  const Recovery r = RunFilter(rows, 1500);
  EXPECT_LE(r.honest_from, std::size_t(1500 + kBoundRows));
}

}  // namespace
}  // namespace pliant::estimation
