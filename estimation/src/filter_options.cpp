// FilterOptions::IsValid and the χ² quantiles: everything the filter decides
// before its first Step().
#include <boost/math/distributions/chi_squared.hpp>
#include <cmath>
#include <string>

#include "chi_squared.h"
#include "pliant/estimation/filter.h"

namespace pliant::estimation {
namespace internal {

double ChiSquaredQuantile(double dof, double p) {
  return boost::math::quantile(boost::math::chi_squared(dof), p);
}

}  // namespace internal

namespace {

bool Fail(std::string* error, const std::string& message) {
  if (error) *error = message;
  return false;
}

}  // namespace

bool FilterOptions::IsValid(std::string* error) const {
  struct Positive {
    const char* name;
    double value;
    const char* unit;
  };
  const Positive positives[] = {
      {"sample_period_s", sample_period_s, "s"},
      {"encoder_noise_rad", encoder_noise_rad, "rad"},
      {"effort_noise_nm", effort_noise_nm, "N·m"},
      {"reference_noise_rad", reference_noise_rad, "rad"},
      {"external_torque_rate_nm", external_torque_rate_nm, "N·m/√s"},
      {"backlash_rate_rad", backlash_rate_rad, "rad/√s"},
      {"backlash_relax_time_s", backlash_relax_time_s, "s"},
      {"backlash_pinned_rate_rad", backlash_pinned_rate_rad, "rad/√s"},
      {"free_tip_rate_rad", free_tip_rate_rad, "rad/√s"},
      {"compliance_scale_sd", compliance_scale_sd, "(a fraction of K)"},
      {"initial_torque_sd_nm", initial_torque_sd_nm, "N·m"},
      {"initial_tip_sd_rad", initial_tip_sd_rad, "rad"},
      {"effort_limit_nm", effort_limit_nm, "N·m"},
      {"backlash_width_noise_multiple", backlash_width_noise_multiple, "multiples of σ_effort"},
      {"acceleration_filter_time_s", acceleration_filter_time_s, "s"},
      {"held_load_inertial_time_s", held_load_inertial_time_s, "s"},
      {"held_load_motion_window_s", held_load_motion_window_s, "s"},
  };
  for (const auto& p : positives) {
    if (!(std::isfinite(p.value) && p.value > 0.0)) {
      return Fail(error, std::string("FilterOptions::") + p.name + " = " + std::to_string(p.value) +
                             " must be finite and > 0 — give it in " + p.unit);
    }
  }
  if (!(std::isfinite(held_load_rest_rate_nm) && held_load_rest_rate_nm >= 0.0)) {
    return Fail(error, "FilterOptions::held_load_rest_rate_nm must be finite and >= 0 — N·m/√s "
                       "a held load drifts with the motor still, e.g. 0.01");
  }
  if (!(std::isfinite(held_load_motion_margin) && held_load_motion_margin >= 1.0)) {
    return Fail(error, "FilterOptions::held_load_motion_margin must be finite and >= 1 — a "
                       "margin on the load the motor's increment can add, e.g. 2");
  }
  if (!(std::isfinite(compliance_scale_rate) && compliance_scale_rate >= 0.0)) {
    return Fail(error, "FilterOptions::compliance_scale_rate must be finite and >= 0 — use 0 "
                       "for a compliance that does not change during the log");
  }
  for (int j = 0; j < 2; ++j) {
    const std::string joint = "[" + std::to_string(j) + "]";
    if (!(std::isnan(backlash_sd_rad[j]) || (std::isfinite(backlash_sd_rad[j]) && backlash_sd_rad[j] >= 0.0))) {
      return Fail(error, "FilterOptions::backlash_sd_rad" + joint + " must be NaN (from the "
                         "parameters' covariance) or finite and >= 0 — σ of the clearance in rad, "
                         "e.g. 0.001");
    }
    if (!(std::isnan(deadzone_width_sd_nm[j]) ||
          (std::isfinite(deadzone_width_sd_nm[j]) && deadzone_width_sd_nm[j] >= 0.0))) {
      return Fail(error, "FilterOptions::deadzone_width_sd_nm" + joint + " must be NaN (from the "
                         "parameters' covariance) or finite and >= 0 — σ of the dead-zone width "
                         "in N·m, e.g. 0.01");
    }
    if (!(std::isnan(effort_offset_sd_nm[j]) ||
          (std::isfinite(effort_offset_sd_nm[j]) && effort_offset_sd_nm[j] >= 0.0))) {
      return Fail(error, "FilterOptions::effort_offset_sd_nm" + joint + " must be NaN (from the "
                         "parameters' covariance) or finite and >= 0 — σ of the bias torque's "
                         "offset in N·m, e.g. 0.02");
    }
  }
  if (!(effort_offset_correlation_s.minCoeff() > 0.0)) {
    return Fail(error, "FilterOptions::effort_offset_correlation_s must be > 0 — seconds, "
                       "infinity for a constant offset");
  }
  if (!(std::isfinite(effort_offset_rate_nm) && effort_offset_rate_nm >= 0.0)) {
    return Fail(error, "FilterOptions::effort_offset_rate_nm must be finite and >= 0 — N·m/√s, "
                       "or 0 for a constant offset");
  }
  if (!(std::isfinite(free_level_drift_nm) && free_level_drift_nm >= 0.0)) {
    return Fail(error, "FilterOptions::free_level_drift_nm must be finite and >= 0 — N·m/√s");
  }
  if (!(std::isfinite(unloaded_start_s) && unloaded_start_s >= 0.0)) {
    return Fail(error, "FilterOptions::unloaded_start_s must be finite and >= 0 — seconds at the "
                       "log's start with the instrument untouched and the arm still, e.g. 0.1, "
                       "or 0 for none");
  }
  if (!(std::isfinite(backlash_transit_noise) && backlash_transit_noise >= 0.0)) {
    return Fail(error, "FilterOptions::backlash_transit_noise must be finite and >= 0 — a "
                       "fraction of the clearance's variance, e.g. 1, or 0 for a certain pull");
  }
  if (!std::isnan(deflection_model_error) &&
      !(std::isfinite(deflection_model_error) && deflection_model_error >= 0.0)) {
    return Fail(error, "FilterOptions::deflection_model_error must be finite and >= 0 — a "
                       "fraction of K·tau, e.g. 0.08, 0 for logs drawn from the model, or NaN "
                       "to take it from the shaft damping");
  }
  if (!(std::isfinite(load_margin_sd) && load_margin_sd >= 0.0)) {
    return Fail(error, "FilterOptions::load_margin_sd must be finite and >= 0 — standard "
                       "deviations of the load estimate, e.g. 2, or 0 to count every load");
  }
  if (!(std::isfinite(scale_hold_exponent) && scale_hold_exponent >= 0.0)) {
    return Fail(error, "FilterOptions::scale_hold_exponent must be finite and >= 0 — a power "
                       "of the load's hold on the wall, e.g. 4, or 0 to let every sure load "
                       "teach the compliance scale");
  }
  if (!(std::isfinite(motor_inertia_kg_m2) && motor_inertia_kg_m2 >= 0.0)) {
    return Fail(error, "FilterOptions::motor_inertia_kg_m2 must be finite and >= 0 — the motor "
                       "inertia reflected at the joint in kg·m², or 0 to read the whole effort "
                       "as load");
  }
  if (!(std::isfinite(inertial_torque_error) && inertial_torque_error >= 0.0)) {
    return Fail(error, "FilterOptions::inertial_torque_error must be finite and >= 0 — a "
                       "fraction of the fitted inertial torque J·θ̈, e.g. 0.3, or 0 for an "
                       "exact fit");
  }
  if (!(std::isfinite(shaft_damping_nm_s_per_rad) && shaft_damping_nm_s_per_rad >= 0.0)) {
    return Fail(error, "FilterOptions::shaft_damping_nm_s_per_rad must be finite and >= 0 — "
                       "the shaft's damping in N·m·s/rad, or 0 for none");
  }
  if (!(effort_offset_bound_sd > 0.0)) {  // NaN fails too; infinity is allowed: no bound
    return Fail(error, "FilterOptions::effort_offset_bound_sd must be > 0 — standard "
                       "deviations of the effort offset, e.g. 3, or infinity for no bound");
  }
  for (const auto& [name, p] : {std::pair<const char*, double>{"gate_probability", gate_probability},
                                {"mismatch_probability", mismatch_probability}}) {
    if (!(p > 0.5 && p < 1.0)) {
      return Fail(error, std::string("FilterOptions::") + name + " = " + std::to_string(p) +
                             " must lie in (0.5, 1) — it is the probability that a measurement "
                             "the model explains passes, e.g. 0.9999 or 0.99");
    }
  }
  if (!(output_step_limit_counts > 0.0)) {  // NaN fails too; +infinity is "off"
    return Fail(error, "FilterOptions::output_step_limit_counts must be > 0 — encoder counts the "
                       "corrected angle may move per step beyond the encoder, e.g. 2, or "
                       "infinity for no limit");
  }
  if (!(seating_bound_weight > 0.0 && seating_bound_weight <= 1.0)) {
    return Fail(error, "FilterOptions::seating_bound_weight must lie in (0, 1] — e.g. 0.9, or 1 "
                       "to keep the tip–load correlation when the tip is seated");
  }
  for (const auto& [name, v] : {std::pair<const char*, double>{"contact_start_rate_hz",
                                                                  contact_start_rate_hz},
                                {"contact_end_rate_hz", contact_end_rate_hz},
                                {"contact_rate_memory_s", contact_rate_memory_s},
                                {"contact_load_sd_nm", contact_load_sd_nm},
                                {"unmodelled_effort_sd_nm", unmodelled_effort_sd_nm},
                                {"unmodelled_effort_memory", unmodelled_effort_memory},
                                {"moving_effort_sd_nm", moving_effort_sd_nm},
                                {"moving_effort_dof", moving_effort_dof},
                                {"internal_inertia_sd_kg_m2", internal_inertia_sd_kg_m2},
                                {"internal_coulomb_sd_nm", internal_coulomb_sd_nm},
                                {"internal_viscous_sd_nm_s", internal_viscous_sd_nm_s},
                                {"internal_bias_error_sd_nm", internal_bias_error_sd_nm},
                                {"coulomb_speed_rad_s", coulomb_speed_rad_s},
                                {"internal_torque_memory_s", internal_torque_memory_s},
                                {"free_level_length_rad", free_level_length_rad},
                                {"free_level_depth_length_m", free_level_depth_length_m},
                                {"unmodelled_effort_speed_rad_s", unmodelled_effort_speed_rad_s},
                                {"time_gap_s", time_gap_s}}) {
    if (!(std::isfinite(v) && v > 0.0)) {
      return Fail(error, std::string("FilterOptions::") + name +
                             " must be finite and > 0 — see filter_options.h for its unit");
    }
  }
  if (reacquire_after < 1 || reacquire_after > 100000) {
    return Fail(error, "FilterOptions::reacquire_after must be in [1, 100000] samples — e.g. 25 "
                       "(17 ms at 1.5 kHz)");
  }
  if (mismatch_window < 10 || mismatch_window > 100000) {
    return Fail(error, "FilterOptions::mismatch_window must be in [10, 100000] samples — e.g. "
                       "300 (0.2 s at 1.5 kHz)");
  }
  return true;
}

}  // namespace pliant::estimation
