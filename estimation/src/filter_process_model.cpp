// The filter's process-model pieces that the filter, its RTS smoother and the
// bench's dense baselines share (filter.h), so that all three predict alike.
#include <algorithm>
#include <cmath>
#include <limits>
#include <string>

#include "pliant/estimation/filter.h"
#include "pliant/models/effects/backlash_hysteresis.h"

namespace pliant::estimation {

/// The σ of a named parameter in the parameters' covariance, NaN without one.
double ParameterStandardDeviation(const models::ModelParameters& p, const std::string& name) {
  if (!p.covariance) return std::numeric_limits<double>::quiet_NaN();
  const auto& names = p.covariance->names;
  const auto it = std::find(names.begin(), names.end(), name);
  const auto i = static_cast<Eigen::Index>(it - names.begin());
  if (it == names.end() || i >= p.covariance->matrix.rows()) {
    return std::numeric_limits<double>::quiet_NaN();
  }
  return std::sqrt(std::max(0.0, p.covariance->matrix(i, i)));
}

double ResolvedStandardDeviation(double option_sd, const models::ModelParameters& p,
                                 const std::string& name, double fallback) {
  if (std::isfinite(option_sd)) return option_sd;
  const double from_covariance = ParameterStandardDeviation(p, name);
  return std::isfinite(from_covariance) ? from_covariance : fallback;
}

double SureLoad(const FilterOptions& o, double tau_nm, double tau_variance_nm2) {
  const double margin = o.load_margin_sd * std::sqrt(std::max(0.0, tau_variance_nm2));
  return std::copysign(std::max(0.0, std::abs(tau_nm) - margin), tau_nm);
}

bool ClearanceLearnable(const FilterOptions& o, double sure_load_nm, double width_nm,
                        double width_sd_nm, double clearance_rad, double clearance_variance_rad2) {
  if (std::abs(sure_load_nm) >= width_nm + o.load_margin_sd * width_sd_nm) return true;
  const double floor_rad = clearance_rad * width_sd_nm / width_nm;
  return clearance_variance_rad2 > floor_rad * floor_rad;
}

double FilterDeadZoneWidth(const FilterOptions& o, const models::JointParameters& joint) {
  const double width_nm =
      joint.deadzone_width_nm > 0.0 ? joint.deadzone_width_nm : std::max(joint.tau_min_nm, 1e-3);
  return std::max(width_nm, o.backlash_width_noise_multiple * o.effort_noise_nm);
}

double ScaleLearningFraction(const FilterOptions& o, double tau_nm, double tau_variance_nm2,
                             double width_nm) {
  const double sure = SureLoad(o, tau_nm, tau_variance_nm2);
  if (sure == 0.0) return 0.0;
  const double hold = models::BacklashHold(sure, width_nm);
  // On the wall (hold 1, the usual loaded step) no pow is needed: Step() is timed.
  return sure / tau_nm * (hold >= 1.0 ? 1.0 : std::pow(hold, o.scale_hold_exponent));
}

double HeldLoadProcessVariance(const FilterOptions& o, double dt, double encoder_increment,
                               double compliance_rad_per_nm, double inertial_torque_nm,
                               double hold) {
  const double free_rate = o.external_torque_rate_nm * o.external_torque_rate_nm * dt;
  if (!o.bound_held_load_rate || !(hold > 0.0)) return free_rate;
  const double moved =
      o.held_load_motion_margin * encoder_increment / std::max(compliance_rad_per_nm, 1e-6);
  const double bound = o.held_load_rest_rate_nm * o.held_load_rest_rate_nm * dt + moved * moved +
                       inertial_torque_nm * inertial_torque_nm * dt / o.held_load_inertial_time_s;
  // Off the wall the encoder moves b as well as the bend, and b may move
  // either way as the load changes: only the held part of the load is bounded.
  const double g = std::min(hold, 1.0);
  return g * std::min(free_rate, bound) + (1.0 - g) * free_rate;
}

void ConfineToClearance(double nominal_clearance_rad, double* clearance_error_rad,
                        double* backlash_rad) {
  *clearance_error_rad =
      std::clamp(*clearance_error_rad, -nominal_clearance_rad, nominal_clearance_rad);
  const double clearance = nominal_clearance_rad + *clearance_error_rad;
  *backlash_rad = std::clamp(*backlash_rad, -clearance, clearance);
}

double HeldEffortVariance(const FilterOptions& o, double inertial_torque_nm) {
  const double misread = o.inertial_torque_error * inertial_torque_nm;
  return o.effort_noise_nm * o.effort_noise_nm + misread * misread;
}

// The fraction of its wall an unloaded shaft forgets in one step: with time
// constant T while the joint moves (an encoder increment of 3 counts or more
// per step counts fully, less in proportion), nothing while it rests. A
// quasi-static log's rows are poses the arm settled at: a shaft that moved
// between two of them has had all the time it needs (its dt, one nominal
// period, is no time at all).
double BacklashRelax(const FilterOptions& o, double dt, double encoder_increment) {
  const double count = 3.4641016151377544 * o.encoder_noise_rad;  // σ_enc = count/√12
  const double moving = std::min(1.0, std::abs(encoder_increment) / (3.0 * count));
  if (o.quasi_static) return moving;
  return -std::expm1(-dt / o.backlash_relax_time_s) * moving;
}

double BacklashProcessVariance(const FilterOptions& o, double dt, bool tip_fixed, double relax,
                               double saturation, double delta_rad) {
  const double prior_variance = delta_rad * delta_rad / 3.0;
  const double pinned = saturation * saturation;  // g: how firmly the load holds the shaft
  // Unloaded, b diffuses: held tip, at σ_b (the arm moves it across the
  // clearance, the encoders follow); free tip, back to the uniform prior as it
  // forgets its wall (the stationary variance of b+ = (1 − r)·b + w is δ²/3).
  const double unloaded = tip_fixed ? o.backlash_rate_rad * o.backlash_rate_rad * dt
                                    : relax * (2.0 - relax) * prior_variance;
  // Partly loaded, held tip: the step pulls b by g toward δ·S(tau/w), a smooth
  // stand-in for a shaft that meets its wall at some load inside w (the
  // simulator's at a few hundredths of a N·m). Where is not known, so the
  // pull is uncertain in proportion to g·(1 − g): zero at no load (no pull)
  // and on the wall (no doubt). Without it the pull, taken as certain, put b
  // short of the wall and dragged s down (docs/filter.md, "The backlash step").
  // Free tip: c = 2. Each pull contracts b's variance by (1 − g)²; with
  // 2·g·(1 − g)·δ²/3 added, the stationary variance (1 − g)/(1 − g/2)·δ²/3 is
  // the prior's δ²/3 as g → 0, so the effort noise of a free tip at rest (g ≈
  // 10⁻³ a sample, a pull of random sign) cannot make b certain. Without it
  // b's σ fell from 0.58 δ to 0.07 δ in 0.3 s while b stayed where the shaft
  // was not: free-tip NEES 23.6 once the simulated shafts start anywhere in
  // their clearance (docs/filter.md, "The backlash step").
  const double transit = (tip_fixed ? o.backlash_transit_noise : 2.0) * pinned * (1.0 - pinned) *
                         prior_variance;
  return (1.0 - pinned) * unloaded + transit +
         o.backlash_pinned_rate_rad * o.backlash_pinned_rate_rad * dt;
}

BacklashVarianceBound BoundBacklashVariance(bool tip_fixed, double propagated_variance,
                                            double process_variance, double prior_variance) {
  BacklashVarianceBound bound;
  bound.process_variance = process_variance;
  if (tip_fixed) return bound;
  double propagated = propagated_variance;
  if (propagated > prior_variance) {
    bound.row_scale = std::sqrt(prior_variance / propagated);
    propagated = prior_variance;
  }
  bound.process_variance = std::min(process_variance, prior_variance - propagated);
  return bound;
}

void SeatingBound(FilterStateMatrix* covariance, double weight) {
  if (!(weight < 1.0)) return;
  FilterStateMatrix& p = *covariance;
  const double load = p(kStateTorque, kStateTorque) / (1.0 - weight);
  p.row(kStateTorque).setZero();
  p.col(kStateTorque).setZero();
  p /= weight;
  p(kStateTorque, kStateTorque) = load;
}

void MotorMotion::Advance(const FilterOptions& o, double dt, double encoder_increment) {
  // Morrison's fading-memory filter of degree 2 (a critically damped α-β-γ
  // tracker, all three closed-loop poles at θ): in steady state the estimate is
  // the quadratic fitted to the encoder angle by least squares with weights θ^k
  // on the sample k steps back, evaluated at the newest sample.
  if (dt != pole_dt_s) {  // the period rarely changes: exp once, not every step
    pole_dt_s = dt;
    pole = std::exp(-dt / o.acceleration_filter_time_s);
  }
  const double theta = pole;
  const double u = 1.0 - theta;
  const double g_velocity = 1.5 * u * u * (1.0 + theta);
  const double g_acceleration = 0.5 * u * u * u;
  // The angle is kept relative to the last encoder reading, so no absolute
  // angle (and no loss of precision far from zero) is needed.
  const double residual = encoder_increment - (position_offset_rad + velocity_rad_s * dt +
                                               0.5 * acceleration_rad_s2 * dt * dt);
  position_offset_rad = -theta * theta * theta * residual;  // prediction + (1 − θ³)·residual
  velocity_rad_s += acceleration_rad_s2 * dt + g_velocity / dt * residual;
  acceleration_rad_s2 += 2.0 * g_acceleration / (dt * dt) * residual;
  if (dt != peak_fade_dt_s) {  // the period rarely changes: exp once, not every step
    peak_fade_dt_s = dt;
    peak_fade = std::exp(-dt / o.held_load_motion_window_s);
  }
  increment_peak_rad = std::max(std::abs(encoder_increment), increment_peak_rad * peak_fade);
}

double MotorMotion::LagSeconds(const FilterOptions& o) {
  // q = t³/6 (unit jerk): the truth is θ̈ = t, the estimate t − lag once the
  // start has faded (θ^k below 1e-16 after 37 T).
  const double dt = o.sample_period_s;
  const int steps = static_cast<int>(std::ceil(40.0 * o.acceleration_filter_time_s / dt)) + 1;
  MotorMotion motion;
  double previous = 0.0;
  for (int k = 1; k <= steps; ++k) {
    const double t = k * dt, q = t * t * t / 6.0;
    motion.Advance(o, dt, q - previous);
    previous = q;
  }
  return steps * dt - motion.acceleration_rad_s2;
}

double MotorMotion::InertialTorque(const FilterOptions& o) const {
  return std::clamp(o.motor_inertia_kg_m2 * acceleration_rad_s2, -o.effort_limit_nm,
                    o.effort_limit_nm);
}

}  // namespace pliant::estimation
