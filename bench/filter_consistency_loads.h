#pragma once
// Helpers of bench/filter_consistency_bench.cpp: the push each run makes, and
// the NEES grouped by how far the push's lighter-loaded joint is into its
// dead zone.
//
// Why the grouping: the filter's backlash model changes regime at the
// dead-zone width w (N·m). A joint at zero load is never pushed across its
// clearance (the divot protocol skips it), one at |tau_j| >= w sits on its
// wall; between the two (a PARTIAL load) the shaft is on its wall while the
// model's pull delta·S(tau/w) is short of it. The paper's 8 directions at
// 0.5 / 1.0 N·m give only min_j |tau_j|/w_j = 0 or >= 1.77, so a figure over
// those pushes says nothing about partial loads; the Monte Carlo study's
// random pushes found the filter overconfident there.
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdio>

#include <Eigen/Core>
#include <boost/math/constants/constants.hpp>
#include <boost/math/distributions/normal.hpp>

#include "pliant/estimation/consistency.h"
#include "pliant/experiments/study.h"

namespace pliant::bench {

inline void PrintTally(const char* name, const estimation::ConsistencyTally& t, bool band) {
  std::printf("  %-34s NEES mean %6.3f over %6ld", name, t.MeanNees(), t.nees_count);
  if (band && t.nees_count > 0) {
    const auto b = estimation::MeanNeesBand95(t.nees_count);
    std::printf(" band [%.3f, %.3f] %s", b.lower, b.upper, b.Contains(t.MeanNees()) ? "in" : "OUT");
  }
  if (t.coverage_count) {
    std::printf("   coverage j1 %5.1f %%  j2 %5.1f %%", 100.0 * t.CoverageFraction(0),
                100.0 * t.CoverageFraction(1));
  }
  std::printf("   max %.1f\n", t.max_nees);
}

/// One run's push in the (tau1, tau2) plane: load = peak·(cos a, sin a).
struct Push {
  double direction_deg = 0.0;
  double peak_torque_nm = 0.0;
  double held_pick = 0.5;  ///< in (0, 1): which held row gives the run's held NEES sample
  /// Where each joint's shaft starts, in (−1, 1) of its clearance δ: uniform,
  /// as the filter's prior says (wherever the last motion left it).
  double shaft_start[2] = {0.0, 0.0};
};

/// Continuous loads: direction uniform on [0, 360) deg and peak uniform on
/// [0.2, 1.2] N·m (the study's Distribution quantiles of the study's
/// SplitMix64 stream for (seed, run)), so partial loads occur as often as
/// random pushes make them. Paper grid: the scenario's 8 directions and its
/// two peaks, from the run index as before (the stream still gives held_pick).
inline Push DrawPush(bool continuous, std::uint64_t seed, int run) {
  using experiments::Distribution;
  static const Distribution direction{Distribution::Kind::kUniform, 0.0, 360.0};
  static const Distribution peak{Distribution::Kind::kUniform, 0.2, 1.2};
  experiments::TrialStream stream(seed, static_cast<std::uint64_t>(run));
  Push push;
  push.direction_deg = direction.Quantile(stream.Uniform());
  push.peak_torque_nm = peak.Quantile(stream.Uniform());
  push.held_pick = stream.Uniform();
  for (double& start : push.shaft_start) start = 2.0 * stream.Uniform() - 1.0;
  if (!continuous) {
    push.direction_deg = 45.0 * ((run / 3) % 8);
    push.peak_torque_nm = (run / 24) % 2 ? 1.0 : 0.5;
  }
  return push;
}

/// NEES and coverage of the held tip per bucket of r = min_j |peak tau_j| / w_j.
class LoadBreakdown {
 public:
  static constexpr int kBuckets = 6;

  static double LoadRatio(const Push& push, const double width_nm[2]) {
    const double a = push.direction_deg * boost::math::constants::degree<double>();
    return std::min(std::abs(push.peak_torque_nm * std::cos(a)) / width_nm[0],
                    std::abs(push.peak_torque_nm * std::sin(a)) / width_nm[1]);
  }
  static int Bucket(double ratio) {
    int b = 0;
    while (b < kBuckets - 1 && ratio >= kEdges[b]) ++b;
    return b;
  }

  /// One held sample of the run (independent across runs)...
  void AddPick(double ratio, const Eigen::Vector2d& e, const Eigen::Matrix2d& p) {
    pick_[Bucket(ratio)].Add(e, p, false);
    ++runs_[Bucket(ratio)];
  }
  /// ...and every k-th held row (correlated: coverage only indicative of the bucket).
  void AddRow(double ratio, const Eigen::Vector2d& e, const Eigen::Matrix2d& p) {
    rows_[Bucket(ratio)].Add(e, p);
  }

  void Print() const {
    std::printf("  tip held, by r = min_j |peak tau_j| / w_j (w: the filter's dead-zone width; "
                "0.01 <= r < 1: one joint partially loaded):\n");
    for (int b = 0; b < kBuckets; ++b) {
      if (runs_[b] == 0) continue;
      char name[64];
      std::snprintf(name, sizeof name, "r %-12s %3d runs, one each", Label(b), runs_[b]);
      PrintTally(name, pick_[b], true);
      std::snprintf(name, sizeof name, "r %-12s every k-th row", Label(b));
      PrintTally(name, rows_[b], false);
    }
  }

 private:
  // 0.01: an axis push (the other joint unloaded, never pushed to its wall).
  static constexpr double kEdges[kBuckets - 1] = {0.01, 0.25, 0.5, 1.0, 2.0};
  static const char* Label(int b) {
    static const char* const labels[kBuckets] = {"[0, 0.01)", "[0.01, 0.25)", "[0.25, 0.5)",
                                                 "[0.5, 1)",  "[1, 2)",       "[2, inf)"};
    return labels[b];
  }
  estimation::ConsistencyTally pick_[kBuckets], rows_[kBuckets];
  int runs_[kBuckets] = {};
};

/// Held rows per joint, grouped by where the truth's shaft is: inside its
/// clearance (|q_enc − q_true| < 0.9·δ), at a wall (0.9–1 δ), or loaded past
/// it (> δ: elastic deflection). Why: a pooled coverage per joint mixes two
/// different error shapes. An unloaded shaft sits anywhere in ±δ, a uniform
/// error whose honest variance δ²/3 puts ±1.96σ at ±1.13δ: those rows are
/// covered 100 % with z² ≈ 1, so a joint that is often unloaded over-covers
/// while its NEES is right. A loaded joint's error is where the model's
/// gaps show (docs/validation.md, section 6).
class ShaftStateBreakdown {
 public:
  void Add(int joint, double deflection_over_clearance, double error_rad, double variance_rad2) {
    const double d = std::abs(deflection_over_clearance);
    Cell& c = cells_[joint][d < 0.9 ? 0 : (d <= 1.0 ? 1 : 2)];
    static const double z95 = boost::math::quantile(boost::math::normal(), 0.975);
    const double z2 = error_rad * error_rad / variance_rad2;
    ++c.count;
    c.covered += z2 <= z95 * z95;
    c.z2_sum += z2;
  }
  void Print() const {
    static const char* const kNames[3] = {"inside clearance", "at a wall", "loaded past it"};
    std::printf("  tip held, by where each joint's shaft truly is (|q_enc - q_true| / delta):\n");
    for (int j = 0; j < 2; ++j) {
      for (int k = 0; k < 3; ++k) {
        const Cell& c = cells_[j][k];
        if (c.count == 0) continue;
        std::printf("  j%d %-16s %6ld rows   mean z^2 %6.3f   coverage %5.1f %%\n", j + 1,
                    kNames[k], c.count, c.z2_sum / double(c.count),
                    100.0 * double(c.covered) / double(c.count));
      }
    }
  }

 private:
  struct Cell {
    long count = 0, covered = 0;
    double z2_sum = 0.0;
  };
  Cell cells_[2][3];
};

}  // namespace pliant::bench
