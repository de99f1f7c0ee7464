#include "pliant/io/parameters_json.h"

#include <cerrno>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <set>
#include <sstream>
#include <utility>
#include <vector>

#include "json_locator.h"
#include "pliant/io/input_error.h"
#include "pliant/io/json_input.h"

namespace pliant::io {
namespace {

using models::ComplianceForm;
using models::JointParameters;
using nlohmann::json;

const char kSeeDocs[] = " (docs/parameters.md shows a complete file)";

using Key = JsonKey;

std::string Dotted(const std::string& pointer) {
  return DottedJsonPointer(pointer, "the top-level object");
}

std::string TypeName(const json& value) { return value.type_name(); }

class Reader {
 public:
  Reader(const std::string& text, const std::string& file) : file_(file), locator_(text) {}

  [[noreturn]] void Fail(const std::string& pointer, std::string problem, std::string fix) const {
    const detail::JsonPosition at = locator_.Find(pointer);
    throw InputError(file_, at.line, at.column, std::move(problem), std::move(fix));
  }

  // An object with no key outside `keys` and every required one present.
  void Object(const json& value, const std::string& pointer, const std::vector<Key>& keys) const {
    if (auto p = CheckJsonObject(value, pointer, keys, "the top-level object", kSeeDocs)) {
      Fail(p->pointer, std::move(p->problem), std::move(p->fix));
    }
  }

  double Number(const json& value, const std::string& pointer, const char* unit) const {
    if (!value.is_number()) {
      Fail(pointer, Dotted(pointer) + " must be a number, found " + TypeName(value),
           "write a number in " + std::string(unit));
    }
    return value.get<double>();
  }

  // An array of numbers; `size` 0 means any non-empty length.
  std::vector<double> Numbers(const json& value, const std::string& pointer, std::size_t size,
                              const char* what) const {
    if (!value.is_array() || value.empty() || (size != 0 && value.size() != size)) {
      const std::string found =
          value.is_array() ? std::to_string(value.size()) + " values" : TypeName(value);
      Fail(pointer, Dotted(pointer) + " must be an array of " + what + ", found " + found,
           "write it as [" + std::string(what) + "]");
    }
    std::vector<double> out;
    for (std::size_t i = 0; i < value.size(); ++i) {
      out.push_back(Number(value[i], pointer + "/" + std::to_string(i), what));
    }
    return out;
  }

  std::string String(const json& value, const std::string& pointer) const {
    if (!value.is_string()) {
      Fail(pointer, Dotted(pointer) + " must be a string, found " + TypeName(value),
           "write it in double quotes");
    }
    return value.get<std::string>();
  }

  // The {"value": ..., "source": ...} wrapper around every scalar.
  const json& Valued(const json& parent, const std::string& pointer, const char* key,
                     JointParameters& joint) const {
    const json& item = parent.at(key);
    const std::string here = pointer + "/" + key;
    Object(item, here, {{"value", true}, {"source", false}});
    Source(item, here, key, joint);
    return item.at("value");
  }

  void Source(const json& item, const std::string& pointer, const char* key,
              JointParameters& joint) const {
    if (item.contains("source"))
      joint.sources[key] = String(item.at("source"), pointer + "/source");
  }

  // "form" is optional and defaults to the paper's table.
  void Bias(const json& bias, const std::string& at, JointParameters& joint) const {
    const bool fourier = bias.is_object() && bias.contains("form") &&
                         String(bias.at("form"), at + "/form") == "fourier";
    if (bias.is_object() && bias.contains("form") && !fourier &&
        bias.at("form").get<std::string>() != "table") {
      Fail(at + "/form", Dotted(at) + ".form is '" + bias.at("form").get<std::string>() + "'",
           "write \"table\" (angle_rad, torque_nm) or \"fourier\" (coefficients a0, a1, b1, …)");
    }
    if (fourier) {
      Object(bias, at, {{"form", true}, {"coefficients", true}, {"depth_slope_nm_per_m", false},
                        {"depth_harmonic_nm_per_m", false}, {"reference_depth_m", false},
                        {"source", false}});
      joint.bias_form = models::BiasForm::kFourier;
      auto& f = joint.bias_fourier;
      f.coefficients = Numbers(bias.at("coefficients"), at + "/coefficients", 0,
                               "a0, a1, b1, … in N·m");
      if (bias.contains("depth_slope_nm_per_m")) {
        f.depth_slope_nm_per_m =
            Number(bias.at("depth_slope_nm_per_m"), at + "/depth_slope_nm_per_m", "N·m/m");
      }
      if (bias.contains("depth_harmonic_nm_per_m")) {  // absent in older files: 0
        const auto c1_d1 = Numbers(bias.at("depth_harmonic_nm_per_m"),
                                   at + "/depth_harmonic_nm_per_m", 2, "c1, d1 in N·m/m");
        f.depth_harmonic_nm_per_m = {c1_d1[0], c1_d1[1]};
      }
      if (bias.contains("reference_depth_m")) {
        f.reference_depth_m = Number(bias.at("reference_depth_m"), at + "/reference_depth_m", "m");
      }
    } else {
      Object(bias, at, {{"form", false}, {"angle_rad", true}, {"torque_nm", true}, {"source", false}});
      joint.bias_torque.angle_rad =
          Numbers(bias.at("angle_rad"), at + "/angle_rad", 0, "angles in rad");
      joint.bias_torque.torque_nm =
          Numbers(bias.at("torque_nm"), at + "/torque_nm", 0, "torques in N·m");
    }
    Source(bias, at, "bias_torque", joint);
  }

  void Compliance(const json& compliance, const std::string& at, JointParameters& joint) const {
    const bool beam = compliance.is_object() && compliance.contains("form") &&
                      String(compliance.at("form"), at + "/form") == "beam_series";
    if (beam) {
      Object(compliance, at, {{"form", true}, {"joint_compliance_rad_per_nm", true},
                              {"structure_compliance_rad_per_n", true},
                              {"shaft_flexibility_per_nm2", true}, {"cannula_length_m", true},
                              {"source", false}});
      joint.compliance.form = ComplianceForm::kBeamSeries;
      auto& c = joint.compliance.cubic.coefficients;
      const char* units[4] = {"rad/(N·m)", "rad/N", "1/(N·m²)", "m"};
      const char* keys[4] = {"joint_compliance_rad_per_nm", "structure_compliance_rad_per_n",
                             "shaft_flexibility_per_nm2", "cannula_length_m"};
      for (int i = 0; i < 4; ++i) c[i] = Number(compliance.at(keys[i]), at + "/" + keys[i], units[i]);
      Source(compliance, at, "compliance", joint);
      return;
    }
    Object(compliance, at, {{"form", true}, {"coefficients", true}, {"source", false}});
    const std::string form = String(compliance.at("form"), at + "/form");
    if (form != "inverse_cubic" && form != "direct_cubic") {
      Fail(at + "/form", Dotted(at) + ".form is '" + form + "'",
           "write \"inverse_cubic\" (the paper's 1/K(L), N·m/rad), \"direct_cubic\" (K(L), "
           "rad/(N·m)) or \"beam_series\" (docs/identification.md)");
    }
    joint.compliance.form =
        form == "inverse_cubic" ? ComplianceForm::kInverseCubic : ComplianceForm::kDirectCubic;
    const auto c = Numbers(compliance.at("coefficients"), at + "/coefficients", 4,
                           "4 numbers c3, c2, c1, c0");
    std::copy(c.begin(), c.end(), joint.compliance.cubic.coefficients.begin());
    Source(compliance, at, "compliance", joint);
  }

  JointParameters Joint(const json& value, const std::string& pointer) const {
    Object(value, pointer,
           {{"bias_torque", true},
            {"compliance", true},
            {"backlash_rad", true},
            {"tau_min_nm", true},
            {"deadzone_width_nm", false},
            {"depth_range_m", true}});
    JointParameters joint;
    Bias(value.at("bias_torque"), pointer + "/bias_torque", joint);
    Compliance(value.at("compliance"), pointer + "/compliance", joint);
    joint.backlash_rad = Number(Valued(value, pointer, "backlash_rad", joint),
                                pointer + "/backlash_rad/value", "rad");
    joint.tau_min_nm =
        Number(Valued(value, pointer, "tau_min_nm", joint), pointer + "/tau_min_nm/value", "N·m");
    joint.deadzone_width_nm = joint.tau_min_nm;
    if (value.contains("deadzone_width_nm")) {
      joint.deadzone_width_nm = Number(Valued(value, pointer, "deadzone_width_nm", joint),
                                       pointer + "/deadzone_width_nm/value", "N·m");
    }
    const auto range = Numbers(Valued(value, pointer, "depth_range_m", joint),
                               pointer + "/depth_range_m/value", 2, "2 numbers min, max in m");
    joint.depth_min_m = range[0];
    joint.depth_max_m = range[1];
    return joint;
  }

  models::ParameterCovariance Covariance(const json& value) const {
    Object(value, "/covariance", {{"names", true}, {"matrix", true}});
    models::ParameterCovariance covariance;
    const json& names = value.at("names");
    if (!names.is_array()) {
      Fail("/covariance/names",
           "covariance.names must be an array of strings, found " + TypeName(names),
           "write it as [\"joint1.backlash_rad\", ...]");
    }
    std::set<std::string> seen;
    for (std::size_t i = 0; i < names.size(); ++i) {
      const std::string at = "/covariance/names/" + std::to_string(i);
      covariance.names.push_back(String(names[i], at));
      if (!seen.insert(covariance.names.back()).second) {
        Fail(at, "covariance.names lists '" + covariance.names.back() + "' twice",
             "name each parameter once");
      }
    }
    const json& matrix = value.at("matrix");
    const std::size_t n = covariance.names.size();
    if (!matrix.is_array() || matrix.size() != n) {
      Fail("/covariance/matrix",
           "covariance.matrix must have one row per name (" + std::to_string(n) + ")",
           "write an n×n array of arrays, in the order of covariance.names");
    }
    covariance.matrix.resize(static_cast<Eigen::Index>(n), static_cast<Eigen::Index>(n));
    for (std::size_t i = 0; i < n; ++i) {
      const auto row = Numbers(matrix[i], "/covariance/matrix/" + std::to_string(i), n,
                               (std::to_string(n) + " numbers").c_str());
      for (std::size_t k = 0; k < n; ++k) covariance.matrix(i, k) = row[k];
    }
    return covariance;
  }

  // ValidateParameters says "jointN: <field> ..."; point at that field.
  [[noreturn]] void FailValidation(const std::string& why) const {
    std::string pointer = "/covariance";
    if (why.rfind("joint", 0) == 0 && why.size() > 6) {
      pointer = "/" + why.substr(0, 6);
      // "compliance" first: its message also mentions depth_range_m as a remedy.
      for (const char* field : {"compliance", "bias_torque", "depth_range_m", "backlash_rad",
                                "tau_min_nm", "deadzone_width_nm"}) {
        if (why.find(field) != std::string::npos) {
          pointer += std::string("/") + field;
          break;
        }
      }
    }
    Fail(pointer, why, std::string("correct the value") + kSeeDocs);
  }

  // "identified_from": [{"file": "calibration.csv", "crc32": "89abcdef"}, …]
  std::vector<models::SourceLog> SourceLogs(const json& logs) const {
    const char* example = "write [{\"file\": \"calibration.csv\", \"crc32\": \"89abcdef\"}], "
                          "or leave identified_from out";
    if (!logs.is_array()) {
      Fail("/identified_from", "identified_from must be an array, found " + TypeName(logs),
           example);
    }
    std::vector<models::SourceLog> out;
    for (std::size_t i = 0; i < logs.size(); ++i) {
      const std::string at = "/identified_from/" + std::to_string(i);
      Object(logs[i], at, {{"file", true}, {"crc32", true}});
      const std::string crc = String(logs[i].at("crc32"), at + "/crc32");
      if (crc.size() != 8 || crc.find_first_not_of("0123456789abcdef") != std::string::npos) {
        Fail(at + "/crc32", Dotted(at + "/crc32") + " is '" + crc + "', not 8 hex digits",
             "write the CRC-32 of the log's bytes in lower-case hex, as pliant identify does");
      }
      out.push_back({String(logs[i].at("file"), at + "/file"),
                     static_cast<std::uint32_t>(std::stoul(crc, nullptr, 16))});
    }
    return out;
  }

  // "effects": {"NAME": {"PARAMETER": {"value": v, "sd": s}, …}, …}
  std::vector<models::EffectParameters> Effects(const json& effects) const {
    if (!effects.is_object()) {
      Fail("/effects", "effects must be an object, found " + TypeName(effects),
           "write {\"held_friction\": {\"held_friction1\": {\"value\": 0.1, \"sd\": 0.01}, …}}");
    }
    std::vector<models::EffectParameters> out;
    for (const auto& [name, parameters] : effects.items()) {
      const std::string at = "/effects/" + name;
      if (!parameters.is_object() || parameters.empty()) {
        Fail(at, "effects." + name + " must be an object of its parameters",
             "write each parameter as {\"value\": number, \"sd\": number}");
      }
      models::EffectParameters effect{name, {}, {}, {}};
      for (const auto& [key, item] : parameters.items()) {
        Object(item, at + "/" + key, {{"value", true}, {"sd", false}});
        effect.parameter_names.push_back(key);
        effect.values.push_back(Number(item.at("value"), at + "/" + key + "/value", "its unit"));
        effect.sd.push_back(item.contains("sd") ? Number(item.at("sd"), at + "/" + key + "/sd",
                                                         "its unit")
                                                : 0.0);
      }
      out.push_back(std::move(effect));
    }
    return out;
  }

 private:
  const std::string& file_;
  detail::JsonLocator locator_;
};

}  // namespace

models::ModelParameters ParseParameters(const std::string& text, const std::string& file) {
  Reader reader(text, file);
  const json document = ParseJsonInput(text, file);
  reader.Object(document, "",
                {{"format", true},
                 {"version", true},
                 {"description", false},
                 {"identified_from", false},
                 {"joint1", true},
                 {"joint2", true},
                 {"covariance", false},
                 {"effects", false}});
  const std::string format = reader.String(document.at("format"), "/format");
  if (format != kParametersFormat) {
    reader.Fail("/format",
                "format is '" + format + "', not '" + std::string(kParametersFormat) + "'",
                "this is not a pliant parameters file; start from data/paper.json");
  }
  const json& version = document.at("version");
  if (!version.is_number_integer() || version.get<long long>() != kParametersVersion) {
    reader.Fail("/version", "version " + version.dump() + " is not supported",
                "this pliant reads version 1; write \"version\": 1 with the fields of "
                "docs/parameters.md");
  }
  models::ModelParameters parameters;
  if (document.contains("description")) {
    parameters.description = reader.String(document.at("description"), "/description");
  }
  if (document.contains("identified_from")) {
    parameters.identified_from = reader.SourceLogs(document.at("identified_from"));
  }
  parameters.joints[0] = reader.Joint(document.at("joint1"), "/joint1");
  parameters.joints[1] = reader.Joint(document.at("joint2"), "/joint2");
  if (document.contains("covariance")) {
    parameters.covariance = reader.Covariance(document.at("covariance"));
  }
  if (document.contains("effects")) parameters.effects = reader.Effects(document.at("effects"));
  const std::string why = models::ValidateParameters(parameters);
  if (!why.empty()) reader.FailValidation(why);
  return parameters;
}

std::string ReadParametersText(const std::string& path) {
  std::error_code ignored;
  if (std::filesystem::is_directory(path, ignored)) {
    throw InputError(path, 0, 0, "is a directory, not a parameters file",
                     "give the path of a .json file; data/paper.json is a complete example");
  }
  std::ifstream in(path, std::ios::binary);
  if (!in) {
    throw InputError(path, 0, 0,
                     std::string("cannot open the parameters file (") + std::strerror(errno) + ")",
                     "check the path; data/paper.json is a complete example");
  }
  std::ostringstream text;
  text << in.rdbuf();
  return text.str();
}

models::ModelParameters ReadParameters(const std::string& path) {
  return ParseParameters(ReadParametersText(path), path);
}

}  // namespace pliant::io
