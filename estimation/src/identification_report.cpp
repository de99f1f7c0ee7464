#include "pliant/estimation/identification_report.h"

#include <cmath>
#include <cstdarg>
#include <cstdio>

namespace pliant::estimation {
namespace {

std::string Line(const char* format, ...) __attribute__((format(printf, 1, 2)));
std::string Line(const char* format, ...) {
  char text[512];
  va_list args;
  va_start(args, format);
  std::vsnprintf(text, sizeof text, format, args);
  va_end(args);
  return std::string(text) + "\n";
}

double Sd(const models::ParameterCovariance& c, std::size_t i) {
  return std::sqrt(std::max(0.0, c.matrix(long(i), long(i))));
}

// The value a covariance name refers to.
double ValueOf(const models::ModelParameters& p, const std::string& name) {
  for (const auto& effect : p.effects) {  // "EFFECT.PARAMETER"
    for (std::size_t k = 0; k < effect.parameter_names.size(); ++k) {
      if (name == effect.name + "." + effect.parameter_names[k]) return effect.values[k];
    }
  }
  if (name.rfind("joint", 0) != 0 || name.size() < 8) return std::nan("");
  const int j = name[5] - '1';
  const auto& joint = p.joints[j];
  const std::string field = name.substr(7);
  if (field == "backlash_rad") return joint.backlash_rad;
  if (field == "deadzone_width_nm") return joint.deadzone_width_nm;
  if (field == "bias_torque.depth_slope_nm_per_m") return joint.bias_fourier.depth_slope_nm_per_m;
  if (field.rfind("bias_torque.coefficients[", 0) == 0) {
    return joint.bias_fourier.coefficients[std::stoul(field.substr(25))];
  }
  if (field.rfind("bias_torque.depth_harmonic_nm_per_m[", 0) == 0) {
    return joint.bias_fourier.depth_harmonic_nm_per_m[std::stoul(field.substr(36)) % 2];
  }
  static const char* kCubic[4] = {"compliance.c3", "compliance.c2", "compliance.c1", "compliance.c0"};
  static const char* kBeam[4] = {"compliance.joint_compliance_rad_per_nm",
                                 "compliance.structure_compliance_rad_per_n",
                                 "compliance.shaft_flexibility_per_nm2", "compliance.cannula_length_m"};
  for (int i = 0; i < 4; ++i) {
    if (field == kCubic[i] || field == kBeam[i]) return joint.compliance.cubic.coefficients[i];
  }
  return std::nan("");
}

}  // namespace

std::array<std::vector<LawComparison>, 2> CompareLaws(const IdentificationResult& result,
                                                      double cannula_length_m) {
  std::array<std::vector<LawComparison>, 2> out;
  for (int j = 0; j < 2; ++j) {
    std::vector<DepthCompliance> points;
    for (const auto& e : result.depth_estimates) {
      if (e.joint == j) points.push_back({e.insertion_depth_m, e.inverse_compliance_nm_per_rad, e.inverse_compliance_sd});
    }
    if (points.size() >= 6) out[j] = CompareComplianceLaws(points, cannula_length_m);
  }
  return out;
}

static const char* MethodName(const std::string& method) {
  if (method == "paper") return "the paper's procedure";
  if (method == "quasi_static") return "quasi-static clamps with the held friction";
  return "joint smoother";
}

std::string IdentificationTable(const IdentificationResult& r, const IdentificationData& data,
                                const std::array<std::vector<LawComparison>, 2>& laws) {
  std::string out = Line("%s, %s law: %zu log(s), %zu rows -> %zu samples (%zu tip held), %.2f s",
                         MethodName(r.method),
                         models::ComplianceFormName(r.parameters.joints[0].compliance.form),
                         data.logs.size(), data.log_rows, data.samples.size(),
                         data.CountTipFixed(), r.seconds);
  if (r.parameters.covariance) {
    const auto& c = *r.parameters.covariance;
    out += Line("  %-44s %14s %12s", "parameter", "value", "± σ");
    for (std::size_t i = 0; i < c.names.size(); ++i) {
      if (Sd(c, i) == 0.0) continue;  // held constant (geometry)
      out += Line("  %-44s %14.6g %12.3g", c.names[i].c_str(), ValueOf(r.parameters, c.names[i]), Sd(c, i));
    }
  }
  out += Line("  compliance at depth (K in rad/(N·m), δ in rad):");
  const auto& range = r.parameters.joints[0];
  for (double depth : {range.depth_min_m, 0.5 * (range.depth_min_m + range.depth_max_m), range.depth_max_m}) {
    const auto at = QueryParametersAtDepth(r.parameters, depth);
    out += Line("    L = %.3f m   K1 = %.5f ± %.5f   K2 = %.5f ± %.5f", depth,
                at.joints[0].compliance_rad_per_nm, at.joints[0].compliance_sd,
                at.joints[1].compliance_rad_per_nm, at.joints[1].compliance_sd);
  }
  for (int j = 0; j < 2; ++j) {
    out += Line("  fit RMS joint %d: angle %.3g rad, effort %.3g N·m", j + 1, r.angle_rms_rad[j],
                r.effort_rms_nm[j]);
  }
  out += Line("  condition number of the parameters' correlation matrix: %.3g", r.condition_number);
  for (int j = 0; j < 2; ++j) {
    if (laws[j].empty()) continue;
    out += Line("  compliance laws, joint %d (per-depth 1/K; lower is better):", j + 1);
    for (const auto& law : laws[j]) {
      out += Line("    %-14s %d terms   held-out RMS %8.4f N·m/rad   AIC %9.2f   BIC %9.2f",
                  models::ComplianceFormName(law.form), law.coefficients, law.held_out_rms, law.aic,
                  law.bic);
    }
  }
  for (const auto& w : r.warnings) out += "  warning: " + w + "\n";
  out += "  solver: " + r.report;
  if (!out.empty() && out.back() != '\n') out += "\n";
  return out;
}

nlohmann::json IdentificationJson(const IdentificationResult& r, const IdentificationData& data,
                                  const std::array<std::vector<LawComparison>, 2>& laws) {
  nlohmann::json out;
  out["method"] = r.method;
  out["law"] = models::ComplianceFormName(r.parameters.joints[0].compliance.form);
  out["logs"] = data.logs;
  out["rows"] = data.log_rows;
  out["samples"] = data.samples.size();
  out["tip_fixed_samples"] = data.CountTipFixed();
  out["seconds"] = r.seconds;
  nlohmann::json parameters = nlohmann::json::array();
  if (r.parameters.covariance) {
    const auto& c = *r.parameters.covariance;
    for (std::size_t i = 0; i < c.names.size(); ++i) {
      parameters.push_back({{"name", c.names[i]}, {"value", ValueOf(r.parameters, c.names[i])}, {"sd", Sd(c, i)}});
    }
  }
  out["parameters"] = parameters;
  out["angle_rms_rad"] = r.angle_rms_rad;
  out["effort_rms_nm"] = r.effort_rms_nm;
  out["condition_number"] = r.condition_number;
  nlohmann::json depths = nlohmann::json::array();
  for (const auto& e : r.depth_estimates) {
    depths.push_back({{"joint", e.joint + 1}, {"depth_m", e.insertion_depth_m},
                      {"inverse_K", e.inverse_compliance_nm_per_rad}, {"inverse_K_sd", e.inverse_compliance_sd},
                      {"delta", e.backlash_rad}, {"delta_sd", e.backlash_sd}});
  }
  out["depth_estimates"] = depths;
  nlohmann::json comparison = nlohmann::json::object();
  for (int j = 0; j < 2; ++j) {
    for (const auto& law : laws[j]) {
      comparison["joint" + std::to_string(j + 1)][models::ComplianceFormName(law.form)] = {
          {"terms", law.coefficients}, {"held_out_rms", law.held_out_rms}, {"aic", law.aic}, {"bic", law.bic}};
    }
  }
  out["law_comparison"] = comparison;
  out["warnings"] = r.warnings;
  out["solver"] = r.report;
  return out;
}

nlohmann::ordered_json DepthJson(const ParametersAtDepth& at) {
  nlohmann::ordered_json out;
  out["depth_m"] = at.insertion_depth_m;
  for (int j = 0; j < 2; ++j) {
    const std::string n = std::to_string(j + 1);
    const auto& joint = at.joints[j];
    out["K" + n] = joint.compliance_rad_per_nm;
    out["K" + n + "_sd"] = joint.compliance_sd;
    out["delta" + n] = joint.backlash_rad;
    out["delta" + n + "_sd"] = joint.backlash_sd;
  }
  for (int j = 0; j < 2; ++j) {
    const std::string n = std::to_string(j + 1);
    out["inverse_K" + n] = at.joints[j].inverse_compliance_nm_per_rad;
    out["inverse_K" + n + "_sd"] = at.joints[j].inverse_compliance_sd;
  }
  out["depth_clamped"] = at.joints[0].depth_clamped || at.joints[1].depth_clamped;
  // A joint whose law the covariance lacks was not identified: its "_sd" of 0 is not known.
  out["in_covariance"] = {at.joints[0].in_covariance, at.joints[1].in_covariance};
  return out;
}

std::string DepthTable(const ParametersAtDepth& at) {
  std::string out = Line("at L = %.4f m:", at.insertion_depth_m);
  for (int j = 0; j < 2; ++j) {
    const auto& joint = at.joints[j];
    out += Line("  joint %d  K = %.5f ± %.5f rad/(N·m)   1/K = %.3f ± %.3f N·m/rad   δ = %.6f ± %.6f rad",
                j + 1, joint.compliance_rad_per_nm, joint.compliance_sd,
                joint.inverse_compliance_nm_per_rad, joint.inverse_compliance_sd, joint.backlash_rad,
                joint.backlash_sd);
  }
  if (at.joints[0].depth_clamped || at.joints[1].depth_clamped) {
    out += "  warning: the depth is outside the parameters' valid range; K is the nearest end's\n";
  }
  return out;
}

nlohmann::json EffectFindingsJson(const std::vector<EffectFinding>& findings) {
  nlohmann::json effects = nlohmann::json::array();
  for (const auto& e : findings) {
    nlohmann::json parameters = nlohmann::json::array();
    for (std::size_t k = 0; k < e.parameters.size(); ++k)
      parameters.push_back({{"name", e.parameter_names[k]}, {"value", e.parameters[k]},
                            {"sd", k < e.parameter_sd.size() ? e.parameter_sd[k] : 0.0}});
    effects.push_back({{"name", e.name}, {"parameters", parameters}});
  }
  return effects;
}

nlohmann::json FreeMotionFitJson(const FreeMotionFit& fit) {
  const nlohmann::json effects = EffectFindingsJson(fit.fitted.effects);
  return {{"logs", fit.logs}, {"rows", fit.rows}, {"blocks", fit.blocks},
          {"block_s", fit.block_s}, {"correlation_s", fit.correlation_s},
          {"effort_rms_before_nm", {fit.rms_before_nm[0], fit.rms_before_nm[1]}},
          {"effort_rms_after_nm", {fit.rms_after_nm[0], fit.rms_after_nm[1]}},
          {"effects", effects}, {"notes", fit.notes}};
}

}  // namespace pliant::estimation
