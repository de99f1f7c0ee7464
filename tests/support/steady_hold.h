#pragma once
// A steady load held on joint 1 with its tip fixed: the scenario of the
// compliance scale's steady-hold drift (docs/filter.md, "Known limitation"),
// shared by tests/estimation/filter_scale_hold_test.cpp, which asserts on it,
// and bench/filter_steady_hold_bench.cpp, which prints it.
#include <algorithm>
#include <cmath>
#include <random>

#include "pliant/estimation/filter.h"
#include "pliant/models/paper_parameters.h"
#include "pliant/models/parameters.h"

namespace pliant::estimation::testing {

struct ScaleTrace {
  double after_1s = 0.0;         // s 0.5 s into the hold
  double at_end = 0.0;           // s at the end
  double sd_at_end = 0.0;        // its standard deviation
  double tip_error_counts = 0.0; // held tip's error at the end, encoder counts
};

// Joint 1 ramped in 0.5 s to `load_fraction`·w and held there for `hold_s`,
// its shaft on the wall all along (q_enc = tip + δ + K·tau, s = 1: the
// simulator's shaft, which meets its wall at once); joint 2 unloaded. The
// efforts carry `effort_noise_scale` times the filter's effort noise (seed 5).
inline ScaleTrace TraceScaleOverHold(const FilterOptions& o, double load_fraction, double hold_s,
                                     double effort_noise_scale) {
  const auto p = models::PaperParameters();
  ComplianceFilter filter(p, o);
  const double depth = 0.15, dt = 1.0 / 1500.0, tip = 0.1;
  const double width = FilterDeadZoneWidth(o, p.joints[0]);
  const double compliance = models::ComplianceAt(p.joints[0], depth);
  const double count = std::sqrt(12.0) * o.encoder_noise_rad;
  std::mt19937_64 rng(5);
  std::normal_distribution<double> normal(0.0, 1.0);
  ScaleTrace trace;
  const int one_second = 1500;
  for (int k = 0; k < int((0.5 + hold_s) / dt); ++k) {
    const double t = k * dt;
    const double tau = load_fraction * width * std::min(1.0, t / 0.5);
    FilterSample s;
    s.time_s = t;
    s.insertion_depth_m = depth;
    s.tip_fixed = true;
    const double q1 = tip + p.joints[0].backlash_rad + compliance * tau;
    s.encoder_rad = {count * std::round(q1 / count), -0.2};
    for (int j = 0; j < 2; ++j) {
      s.effort_nm[j] = models::BiasTorqueAt(p.joints[j], s.encoder_rad[j], depth) +
                       (j == 0 ? tau : 0.0) +
                       effort_noise_scale * o.effort_noise_nm * normal(rng);
    }
    const double scale = filter.Step(s).compliance_scale[0];
    if (k == one_second) trace.after_1s = scale;
    trace.at_end = scale;
  }
  const FilterJointState& x = filter.joint_state(0);
  trace.sd_at_end = std::sqrt(x.covariance(kStateScale, kStateScale));
  trace.tip_error_counts = (x.mean[kStateTip] - tip) / count;
  return trace;
}

}  // namespace pliant::estimation::testing
