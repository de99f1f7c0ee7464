// Writing parameters files: the inverse of parameters_json.cpp, key for key.

#include <cstdio>
#include <set>
#include <stdexcept>
#include <vector>

#include "pliant/io/atomic_file.h"
#include "pliant/io/parameters_json.h"

namespace pliant::io {
namespace {

using models::ComplianceForm;
using models::JointParameters;

nlohmann::ordered_json Sourced(nlohmann::ordered_json item, const JointParameters& joint,
                               const char* key) {
  const auto found = joint.sources.find(key);
  if (found != joint.sources.end()) item["source"] = found->second;
  return item;
}

nlohmann::ordered_json BiasJson(const JointParameters& joint) {
  if (joint.bias_form == models::BiasForm::kTable) {
    return {{"angle_rad", joint.bias_torque.angle_rad}, {"torque_nm", joint.bias_torque.torque_nm}};
  }
  const auto& f = joint.bias_fourier;
  nlohmann::ordered_json out = {{"form", "fourier"},
                                {"coefficients", f.coefficients},
                                {"depth_slope_nm_per_m", f.depth_slope_nm_per_m}};
  // Written only when nonzero, so that readers without the term still accept the file.
  if (f.depth_harmonic_nm_per_m[0] != 0.0 || f.depth_harmonic_nm_per_m[1] != 0.0) {
    out["depth_harmonic_nm_per_m"] = f.depth_harmonic_nm_per_m;
  }
  out["reference_depth_m"] = f.reference_depth_m;
  return out;
}

nlohmann::ordered_json ComplianceJson(const JointParameters& joint) {
  const auto& c = joint.compliance.cubic.coefficients;
  if (joint.compliance.form == ComplianceForm::kBeamSeries) {
    return {{"form", "beam_series"},
            {"joint_compliance_rad_per_nm", c[models::kJointComplianceRadPerNm]},
            {"structure_compliance_rad_per_n", c[models::kStructureComplianceRadPerN]},
            {"shaft_flexibility_per_nm2", c[models::kShaftFlexibilityPerNm2]},
            {"cannula_length_m", c[models::kCannulaLengthM]}};
  }
  return {{"form", models::ComplianceFormName(joint.compliance.form)},
          {"coefficients", {c[0], c[1], c[2], c[3]}}};
}

nlohmann::ordered_json JointToJson(const JointParameters& joint) {
  for (const auto& [key, text] : joint.sources) {
    static const std::set<std::string> kFields = {"bias_torque",       "compliance",
                                                  "backlash_rad",      "tau_min_nm",
                                                  "deadzone_width_nm", "depth_range_m"};
    if (kFields.count(key) == 0) {
      throw std::invalid_argument("parameter source '" + key + "' names no parameter field");
    }
  }
  nlohmann::ordered_json out;
  out["bias_torque"] = Sourced(BiasJson(joint), joint, "bias_torque");
  out["compliance"] = Sourced(ComplianceJson(joint), joint, "compliance");
  out["backlash_rad"] = Sourced({{"value", joint.backlash_rad}}, joint, "backlash_rad");
  out["tau_min_nm"] = Sourced({{"value", joint.tau_min_nm}}, joint, "tau_min_nm");
  out["deadzone_width_nm"] =
      Sourced({{"value", joint.deadzone_width_nm}}, joint, "deadzone_width_nm");
  out["depth_range_m"] =
      Sourced({{"value", {joint.depth_min_m, joint.depth_max_m}}}, joint, "depth_range_m");
  return out;
}

// Key order as in docs/parameters.md, so written files read like the example.
nlohmann::ordered_json OrderedJson(const models::ModelParameters& parameters) {
  nlohmann::ordered_json out;
  out["format"] = kParametersFormat;
  out["version"] = kParametersVersion;
  out["description"] = parameters.description;
  if (!parameters.identified_from.empty()) {
    nlohmann::ordered_json logs = nlohmann::ordered_json::array();
    for (const auto& log : parameters.identified_from) {
      char crc[9];
      std::snprintf(crc, sizeof crc, "%08x", static_cast<unsigned>(log.crc32));
      logs.push_back({{"file", log.file}, {"crc32", crc}});
    }
    out["identified_from"] = logs;
  }
  out["joint1"] = JointToJson(parameters.joints[0]);
  out["joint2"] = JointToJson(parameters.joints[1]);
  if (parameters.covariance) {
    const auto& covariance = *parameters.covariance;
    nlohmann::ordered_json matrix = nlohmann::ordered_json::array();
    for (Eigen::Index i = 0; i < covariance.matrix.rows(); ++i) {
      std::vector<double> row(covariance.matrix.cols());
      for (Eigen::Index k = 0; k < covariance.matrix.cols(); ++k) row[k] = covariance.matrix(i, k);
      matrix.push_back(row);
    }
    out["covariance"] = {{"names", covariance.names}, {"matrix", matrix}};
  }
  if (!parameters.effects.empty()) {
    nlohmann::ordered_json effects = nlohmann::ordered_json::object();
    for (const auto& effect : parameters.effects) {
      nlohmann::ordered_json item = nlohmann::ordered_json::object();
      for (std::size_t k = 0; k < effect.values.size(); ++k) {
        item[effect.parameter_names[k]] = {{"value", effect.values[k]}, {"sd", effect.sd[k]}};
      }
      effects[effect.name] = item;
    }
    out["effects"] = effects;
  }
  return out;
}

}  // namespace

nlohmann::json ParametersToJson(const models::ModelParameters& parameters) {
  return OrderedJson(parameters);
}

void WriteParameters(const std::string& path, const models::ModelParameters& parameters) {
  WriteFileAtomically(path, OrderedJson(parameters).dump(2) + "\n");
}

}  // namespace pliant::io
