#include "filter_options.h"

#include <string>
#include <variant>

#include <pybind11/eigen.h>
#include <pybind11/stl.h>

#include "pliant/io/input_error.h"

namespace pliant::python {
namespace py = pybind11;
namespace {

using estimation::FilterOptions;
using Field = std::variant<double FilterOptions::*, bool FilterOptions::*, int FilterOptions::*,
                           Eigen::Vector2d FilterOptions::*>;

// The options `pliant filter` offers, under their C++ names, and two more a
// control loop needs (its period, a reference's noise).
const std::pair<const char*, Field> kFields[] = {
    {"sample_period_s", &FilterOptions::sample_period_s},
    {"encoder_noise_rad", &FilterOptions::encoder_noise_rad},
    {"effort_noise_nm", &FilterOptions::effort_noise_nm},
    {"effort_noise_from_log", &FilterOptions::effort_noise_from_log},
    {"reference_noise_rad", &FilterOptions::reference_noise_rad},
    {"fuse_log_reference", &FilterOptions::fuse_log_reference},
    {"external_torque_rate_nm", &FilterOptions::external_torque_rate_nm},
    {"compliance_scale_sd", &FilterOptions::compliance_scale_sd},
    {"backlash_sd_rad", &FilterOptions::backlash_sd_rad},
    {"deadzone_width_sd_nm", &FilterOptions::deadzone_width_sd_nm},
    {"effort_offset_sd_nm", &FilterOptions::effort_offset_sd_nm},
    {"effort_offset_correlation_s", &FilterOptions::effort_offset_correlation_s},
    {"effort_colour_from_log", &FilterOptions::effort_colour_from_log},
    {"unloaded_start_s", &FilterOptions::unloaded_start_s},
    {"motor_inertia_kg_m2", &FilterOptions::motor_inertia_kg_m2},
    {"shaft_damping_nm_s_per_rad", &FilterOptions::shaft_damping_nm_s_per_rad},
    {"deflection_model_error", &FilterOptions::deflection_model_error},
    {"inertial_torque_error", &FilterOptions::inertial_torque_error},
    {"align_inertial_torque", &FilterOptions::align_inertial_torque},
    {"bound_held_load_rate", &FilterOptions::bound_held_load_rate},
    {"load_follows_motor", &FilterOptions::load_follows_motor},
    {"output_step_limit_counts", &FilterOptions::output_step_limit_counts},
    {"gate_probability", &FilterOptions::gate_probability},
    {"mismatch_window", &FilterOptions::mismatch_window},
    // Contact without the tip_fixed hint (docs/decisions/contact-prior.md, contact-rates.md).
    {"infer_contact", &FilterOptions::infer_contact},
    {"contact_start_rate_hz", &FilterOptions::contact_start_rate_hz},
    {"contact_end_rate_hz", &FilterOptions::contact_end_rate_hz},
    {"learn_contact_rates", &FilterOptions::learn_contact_rates},
    {"contact_rate_memory_s", &FilterOptions::contact_rate_memory_s},
    {"free_level", &FilterOptions::free_level},  // (docs/decisions/contact-free-level.md)
    // What the effort holds besides a load while the arm moves (its priors).
    {"contact_load_sd_nm", &FilterOptions::contact_load_sd_nm},
    {"unmodelled_effort_sd_nm", &FilterOptions::unmodelled_effort_sd_nm},
    {"moving_effort_sd_nm", &FilterOptions::moving_effort_sd_nm},
    {"unmodelled_effort_speed_rad_s", &FilterOptions::unmodelled_effort_speed_rad_s},
    {"internal_coulomb_sd_nm", &FilterOptions::internal_coulomb_sd_nm},
    {"internal_viscous_sd_nm_s", &FilterOptions::internal_viscous_sd_nm_s},
    {"internal_inertia_sd_kg_m2", &FilterOptions::internal_inertia_sd_kg_m2},
};

std::string Names() {
  std::string names;
  for (const auto& [name, field] : kFields) {
    names += (names.empty() ? "" : ", ") + std::string(name);
  }
  return names;
}

void Set(FilterOptions& options, const std::string& name, const Field& field,
         const py::handle& value) {
  try {
    std::visit(
        [&](auto member) {
          using T = std::decay_t<decltype(options.*member)>;
          if constexpr (std::is_same_v<T, Eigen::Vector2d>) {
            // One number for both joints, or (joint 1, joint 2).
            if (py::isinstance<py::float_>(value) || py::isinstance<py::int_>(value)) {
              (options.*member).setConstant(value.cast<double>());
            } else {
              (options.*member) = value.cast<Eigen::Vector2d>();
            }
          } else {
            if (std::is_same_v<T, bool> != py::isinstance<py::bool_>(value)) throw py::cast_error();
            options.*member = value.cast<T>();
          }
        },
        field);
  } catch (const py::cast_error&) {
    throw io::InputError("filter option " + name, 0, 0,
                         "cannot use " + py::repr(value).cast<std::string>(),
                         "give " + std::string(std::holds_alternative<bool FilterOptions::*>(field)
                                                   ? "True or False"
                                                   : "a number (a pair for the two joints)"));
  }
}

}  // namespace

FilterOptions FilterOptionsFrom(const py::dict& given) {
  FilterOptions options;
  for (const auto& [key, value] : given) {
    const auto name = key.cast<std::string>();
    bool known = false;
    for (const auto& [field_name, field] : kFields) {
      if (name == field_name) Set(options, name, field, value), known = true;
    }
    if (!known) {
      throw io::InputError("filter option " + name, 0, 0, "unknown option",
                           "use one of: " + Names() + " (docs/python.md)");
    }
  }
  // A tare needs an offset to learn: as `pliant filter --unloaded-start`, the
  // offset's σ is then the parameters' unless given (filter_options.h: NaN).
  if (options.unloaded_start_s > 0.0 && !given.contains("effort_offset_sd_nm")) {
    options.effort_offset_sd_nm.setConstant(FilterOptions::kFromParameters);
  }
  std::string error;
  if (!options.IsValid(&error)) {
    const std::string prefix = "FilterOptions::", dash = " \u2014 ";
    if (error.rfind(prefix, 0) == 0) error.erase(0, prefix.size());
    const std::size_t at = error.find(dash);
    const std::string fix =
        at == std::string::npos ? "see docs/filter.md" : error.substr(at + dash.size());
    throw io::InputError("filter options", 0, 0, error.substr(0, at), fix);
  }
  return options;
}

py::dict FilterOptionDefaults() {
  const FilterOptions defaults;
  py::dict out;
  for (const auto& [name, field] : kFields) {
    std::visit([&](auto member) { out[name] = py::cast(defaults.*member); }, field);
  }
  return out;
}

}  // namespace pliant::python
