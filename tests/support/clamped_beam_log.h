#pragma once
// A quasi-static log of the paper's calibration, for identification tests:
// a bias sweep with the tip free, then for each joint and depth the tip clamped
// and the joint stepped (0.25 mm at the tip) until the external torque passes
// 1 N·m, back to −1 N·m and back past the start, one averaged row per hold.
// The truth composes the models/ effects with a hard clearance of ±delta: the
// shaft is free inside it (no load) and rests on the wall beyond it; or, with
// take_up_nm > 0, the clearance taken up as the load builds, pliant's dead zone
// delta·S(tau / take_up_nm) (models/smooth.h).

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <cstdint>
#include <random>
#include <vector>

#include <boost/math/tools/roots.hpp>

#include "paper_parameters.h"
#include "pliant/io/log.h"
#include "pliant/io/log_writer.h"
#include "pliant/models/parameters.h"
#include "pliant/models/smooth.h"

namespace pliant::testing {

struct CalibrationLogSpec {
  models::ModelParameters truth;            ///< compliance law and backlash
  std::vector<double> depths_m;
  std::vector<int> joints{0, 1};
  double effort_noise_nm = 0.0025;           ///< of one averaged row
  double torque_limit_nm = 1.0;
  bool reversals = true;                     ///< false: push one way only
  bool bias_sweep = true;
  std::vector<double> sweep_depths_m{0.10, 0.16, 0.22};  ///< depths of the bias sweep
  bool clamp = true;                         ///< false: no tip_fixed rows at all
  double take_up_nm = 0.0;                   ///< > 0: the dead zone's width w (else a hard wall)
  /// B (N·m/m): joint 2's gravity harmonic grows with depth, B·L·sin q2 added
  /// to TrueBias (the instrument's centre of mass moves out along the shaft).
  double depth_gravity_nm_per_m = 0.0;
  unsigned seed = 1;
};

/// The truth's bias: smooth in the angle, linear in depth on joint 2.
inline double TrueBias(int joint, double q, double depth_m) {
  return joint == 0 ? 0.19 + 0.06 * std::sin(q) - 0.025 * std::cos(2.0 * q)
                    : 0.03 + 0.12 * std::sin(q) - 0.2419 * (depth_m - 0.155);
}

inline io::Log MakeCalibrationLog(const CalibrationLogSpec& spec) {
  io::Log log;
  log.header.columns = {"t", "q1", "q2", "q3", "tau1", "tau2", "tip_fixed", "segment"};
  std::mt19937 rng(spec.seed);
  std::normal_distribution<double> noise(0.0, spec.effort_noise_nm);
  double t = 0.0;
  int segment = 0;
  auto emit = [&](double q1, double q2, double depth, double load1, double load2, bool fixed) {
    log.values.insert(log.values.end(),
                      {t, q1, q2, depth, TrueBias(0, q1, depth) + load1 + noise(rng),
                       TrueBias(1, q2, depth) + spec.depth_gravity_nm_per_m * depth * std::sin(q2) +
                           load2 + noise(rng),
                       fixed ? 1.0 : 0.0,
                       double(segment)});
    t += 0.5;
  };
  if (spec.bias_sweep) {
    for (double depth : spec.sweep_depths_m) {
      ++segment;
      for (int k = -18; k <= 18; ++k) emit(k * 5.0 * M_PI / 180.0, 0.0, depth, 0.0, 0.0, false);
      for (int k = -10; k <= 10; ++k) emit(0.0, k * 5.0 * M_PI / 180.0, depth, 0.0, 0.0, false);
    }
  }
  if (!spec.clamp) return log;
  for (double depth : spec.depths_m) {
    for (int j : spec.joints) {
      ++segment;
      const auto& joint = spec.truth.joints[j];
      const double k = models::ComplianceAt(joint, depth), delta = joint.backlash_rad;
      // Load of a hard clearance: zero inside ±delta, elastic beyond it.
      // With a take-up, q = delta·S(tau / w) + k·tau, increasing in tau, and
      // tau lies within ±delta / k of q / k.
      auto load = [&](double q) {
        if (spec.take_up_nm <= 0.0)
          return q > delta ? (q - delta) / k : (q < -delta ? (q + delta) / k : 0.0);
        const auto angle = [&](double tau) {
          return delta * models::SmoothSaturation(tau / spec.take_up_nm) + k * tau - q;
        };
        std::uintmax_t iterations = 200;
        const auto root = boost::math::tools::toms748_solve(
            angle, (q - delta) / k - 1e-9, (q + delta) / k + 1e-9,
            boost::math::tools::eps_tolerance<double>(50), iterations);
        return 0.5 * (root.first + root.second);
      };
      const double step = 0.25e-3 / depth;
      auto row = [&](double q) {
        emit(j == 0 ? q : 0.0, j == 1 ? q : 0.0, depth, j == 0 ? load(q) : 0.0,
             j == 1 ? load(q) : 0.0, true);
      };
      double q = 0.0;
      for (; load(q) < spec.torque_limit_nm; q += step) row(q);
      if (!spec.reversals) continue;
      for (; load(q) > -spec.torque_limit_nm; q -= step) row(q);
      for (; q < 0.0; q += step) row(q);
    }
  }
  return log;
}

/// The calibration log of the paper's instrument (spec.truth set to the
/// paper's parameters), written to dir/calibration.csv; returns its path.
inline std::filesystem::path WritePaperCalibrationLog(const std::filesystem::path& dir,
                                                      CalibrationLogSpec spec) {
  spec.truth = models::testing::PaperParameters();
  const std::filesystem::path path = dir / "calibration.csv";
  io::WriteLog(path.string(), MakeCalibrationLog(spec));
  return path;
}

}  // namespace pliant::testing
