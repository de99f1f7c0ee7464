// A tip held where it is while a load bends the shaft, on the parameters'
// own model: the sample a test feeds the filter without the tip_fixed hint.
#pragma once

#include <cmath>
#include <random>

#include <Eigen/Core>

#include "pliant/estimation/filter.h"
#include "pliant/models/effects/backlash_hysteresis.h"
#include "pliant/models/parameters.h"

namespace pliant::estimation::testing {

// The arm's own torque the tests put into a moving motor's effort (N·m):
// J·θ̈ + Coulomb + viscous, about the level of the real dVRK bag's
// unmodelled residual (0.1 N·m RMS in free motion).
inline double ArmTorqueNm(double acceleration_rad_s2, double speed_rad_s) {
  return 0.04 * acceleration_rad_s2 + 0.08 * std::tanh(speed_rad_s / 0.05) + 0.03 * speed_rad_s;
}

// The shaft's offset moves by the hysteresis (`backlash`, rad, carried from
// sample to sample), the encoder reads tip + b + K(L)·τ and the effort the
// bias table at that angle + τ + `table_error_nm` (what the table misses),
// each with the options' noise (`normal`: N(0, 1), drawn encoder then effort,
// joint by joint).
inline FilterSample PushedTipSample(const models::ModelParameters& p, const FilterOptions& o,
                                    double time_s, double depth_m, const Eigen::Vector2d& tip_rad,
                                    const Eigen::Vector2d& load_nm, double table_error_nm,
                                    Eigen::Vector2d* backlash, std::mt19937_64* rng,
                                    std::normal_distribution<double>* normal) {
  FilterSample s;
  s.time_s = time_s;
  s.insertion_depth_m = depth_m;
  for (int j = 0; j < 2; ++j) {
    const auto& jp = p.joints[j];
    (*backlash)[j] = models::BacklashHysteresisStep((*backlash)[j], load_nm[j], jp.backlash_rad,
                                                    jp.deadzone_width_nm);
    s.encoder_rad[j] = tip_rad[j] + (*backlash)[j] + models::ComplianceAt(jp, depth_m) * load_nm[j] +
                       o.encoder_noise_rad * (*normal)(*rng);
    s.effort_nm[j] = models::BiasTorqueAt(jp, s.encoder_rad[j], depth_m) + table_error_nm +
                     load_nm[j] + o.effort_noise_nm * (*normal)(*rng);
  }
  return s;
}

}  // namespace pliant::estimation::testing
