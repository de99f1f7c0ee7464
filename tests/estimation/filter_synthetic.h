#pragma once
// Logs drawn from the filter's own model (filter.h), for tests that need the
// model to be exactly right: NEES and coverage, NIS false alarms, Joseph
// updates against a dense filter. The truth per joint: a constant tip angle
// (or a free tip moving slowly), a load that pushes and reverses, the
// backlash offset advanced by BacklashHysteresisStep, a compliance scale
// drawn from the filter's prior; encoders and efforts with Gaussian noise.

#include <cmath>
#include <random>
#include <vector>

#include "../support/paper_parameters.h"
#include "pliant/estimation/filter.h"
#include "pliant/models/effects/backlash_hysteresis.h"
#include "pliant/models/effects/shaft_damping.h"
#include "pliant/models/parameters.h"

namespace pliant::estimation::testing {

inline constexpr double kNoBend = 1e300;  // no previous sample

struct SyntheticRun {
  std::vector<FilterSample> samples;
  std::vector<Eigen::Vector2d> truth;  ///< q_tip
  std::vector<Eigen::Vector2d> true_torque;
  Eigen::Vector2d true_scale{1.0, 1.0};
};

struct SyntheticOptions {
  double duration_s = 6.0;
  double rate_hz = 1500.0;
  double depth_m = 0.15;
  bool tip_fixed = true;
  double peak_torque_nm = 1.0;
  double push_period_s = 3.0;    ///< one push each way per period
  double load_noise_nm = 0.0;    ///< random-walk wander of the load, N·m/√s
  double drift_on_s = -1.0;      ///< from this time, an effort offset (a hidden effect)
  double drift_nm = 0.0;
  bool draw_scale = true;        ///< compliance scale from the prior; else 1
  /// Each shaft starts uniformly anywhere in its clearance, as a real one
  /// does; false: in the middle, the filter's prior mean.
  bool draw_shaft_start = false;
  /// Else where both shafts start, a share of their clearance in [−1, 1].
  double shaft_start_share = 0.0;
  /// The load is 0 before this time (the arm at rest, untouched); the pushes
  /// and the wander start from it.
  double unloaded_s = 0.0;
  /// c_s, N·m·s/rad: the effort also carries c_s·g·q̇ (models::ShaftDampingTorque),
  /// g the true load's hold on the wall, q̇ the noise-free encoder's rate.
  double shaft_damping_nm_s_per_rad = 0.0;
  unsigned seed = 1;
};

// A log drawn from the filter's own model has no deflection error beyond s:
// the allowance for the plant's is off; and it is drawn with the parameters'
// own clearance and bias.
inline FilterOptions ModelLogOptions() {
  FilterOptions o;
  o.deflection_model_error = 0.0;
  o.backlash_sd_rad.setZero();
  o.effort_offset_sd_nm.setZero();
  // Every free sample of such a log carries a load (its effort residual is all load).
  o.infer_contact = false;
  return o;
}

inline SyntheticRun MakeSyntheticRun(const models::ModelParameters& p, const FilterOptions& o,
                                     const SyntheticOptions& s) {
  std::mt19937_64 rng(s.seed);
  std::normal_distribution<double> normal(0.0, 1.0);
  SyntheticRun run;
  const double dt = 1.0 / s.rate_hz;
  const int n = int(s.duration_s * s.rate_hz);
  Eigen::Vector2d tip(0.1, -0.2), backlash(0.0, 0.0), wander(0.0, 0.0);
  Eigen::Vector2d last_bend{kNoBend, kNoBend};  // the noise-free encoder of the last sample
  if (s.draw_scale) {
    run.true_scale << 1.0 + o.compliance_scale_sd * normal(rng),
        1.0 + o.compliance_scale_sd * normal(rng);
  }
  std::uniform_real_distribution<double> share(-1.0, 1.0);
  for (int j = 0; j < 2; ++j) {
    const double start = s.draw_shaft_start ? share(rng) : s.shaft_start_share;
    backlash[j] = start * p.joints[j].backlash_rad;
  }
  constexpr double kPi = 3.14159265358979323846;
  for (int k = 0; k < n; ++k) {
    const double t = k * dt;
    FilterSample sample;
    sample.time_s = t;
    sample.insertion_depth_m = s.depth_m;
    sample.tip_fixed = s.tip_fixed;
    if (!s.tip_fixed) tip += Eigen::Vector2d(0.05, -0.03) * dt;  // slow free motion
    Eigen::Vector2d torque(0.0, 0.0);
    if (t >= s.unloaded_s) {
      const double phase = 2.0 * kPi * (t - s.unloaded_s) / s.push_period_s;
      torque << s.peak_torque_nm * std::sin(phase), -0.6 * s.peak_torque_nm * std::sin(phase + 0.7);
      wander += s.load_noise_nm * std::sqrt(dt) * Eigen::Vector2d(normal(rng), normal(rng));
      torque += wander;
    }
    for (int j = 0; j < 2; ++j) {
      const auto& jp = p.joints[j];
      backlash[j] = models::BacklashHysteresisStep(backlash[j], torque[j], jp.backlash_rad,
                                                   jp.deadzone_width_nm);
      const double k_rad_per_nm = models::ComplianceAt(jp, s.depth_m);
      const double bend = tip[j] + backlash[j] + run.true_scale[j] * k_rad_per_nm * torque[j];
      sample.encoder_rad[j] = bend + o.encoder_noise_rad * normal(rng);
      const double drift = (s.drift_on_s >= 0.0 && t >= s.drift_on_s) ? s.drift_nm : 0.0;
      const double damping =
          last_bend[j] == kNoBend
              ? 0.0
              : models::ShaftDampingTorque(s.shaft_damping_nm_s_per_rad, (bend - last_bend[j]) / dt,
                                           models::BacklashHold(torque[j], jp.deadzone_width_nm));
      last_bend[j] = bend;
      sample.effort_nm[j] = models::BiasTorqueAt(jp, sample.encoder_rad[j], s.depth_m) +
                            torque[j] + drift + damping + o.effort_noise_nm * normal(rng);
    }
    run.samples.push_back(sample);
    run.truth.push_back(tip);
    run.true_torque.push_back(torque);
  }
  return run;
}

}  // namespace pliant::estimation::testing
