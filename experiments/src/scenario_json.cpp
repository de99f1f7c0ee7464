// Scenario files (docs/simulator.md): checked section by section; unknown
// keys, missing keys and out-of-range values are InputErrors at their line.
#include <cmath>
#include <fstream>
#include <sstream>

#include "pliant/estimation/effect_catalogue.h"
#include "pliant/io/json_input.h"
#include "scenario_json_parts.h"

namespace pliant::experiments {
namespace detail {
namespace {

constexpr const char* kFormat = "pliant-scenario";
constexpr double kInf = 1e300;

void Optional(const ScenarioReader& r, const json& obj, const std::string& p, const char* key,
              double& target, const char* unit, double lower, double upper) {
  if (obj.contains(key)) target = r.Number(obj[key], p + "/" + key, unit, lower, upper);
}

void Optional(const ScenarioReader& r, const json& obj, const std::string& p, const char* key,
              Eigen::Vector2d& target, const char* unit, double lower, double upper) {
  if (obj.contains(key)) target = r.Pair(obj[key], p + "/" + key, unit, lower, upper);
}

models::BiasTorqueTable ReadTable(const ScenarioReader& r, const json& t, const std::string& p) {
  r.Object(t, p, {{"angle_rad", true}, {"torque_nm", true}});
  models::BiasTorqueTable table;
  table.angle_rad = r.Numbers(t["angle_rad"], p + "/angle_rad", 0, "rad", -3.2, 3.2);
  table.torque_nm =
      r.Numbers(t["torque_nm"], p + "/torque_nm", table.angle_rad.size(), "N·m", -3.316, 3.316);
  return table;
}

void ReadTruth(const ScenarioReader& r, const json& t, Truth& out) {
  const std::string p = "/truth";
  r.Object(t, p,
           {{"compliance", true},
            {"backlash_rad", true},
            {"backlash_centre_rad", false},
            {"initial_shaft_offset_rad", false},
            {"bias_torque", false}});
  const json& c = t["compliance"];
  const std::string pc = p + "/compliance";
  r.Object(c, pc, {{"form", false}, {"joint1", true}, {"joint2", true}, {"depth_range_m", false}});
  models::ComplianceForm form = models::ComplianceForm::kInverseCubic;
  if (c.contains("form")) {
    const std::string name = r.String(c["form"], pc + "/form");
    if (name == "direct_cubic") {
      form = models::ComplianceForm::kDirectCubic;
    } else if (name != "inverse_cubic") {
      r.Fail(pc + "/form", "unknown compliance form '" + name + "'",
             "use inverse_cubic (the paper's 1/K(L)) or direct_cubic (the dVRK file's K(L))");
    }
  }
  Eigen::Vector2d range(0.09, 0.22);
  Optional(r, c, pc, "depth_range_m", range, "m", 1e-3, 0.3);
  const Eigen::Vector2d backlash = r.Pair(t["backlash_rad"], p + "/backlash_rad", "rad", 0, 0.05);
  for (int j = 0; j < 2; ++j) {
    auto& joint = out.joints[j];
    const std::string key = j == 0 ? "joint1" : "joint2";
    const auto k =
        r.Numbers(c[key], pc + "/" + key, 4, "(cubic coefficients, L³ first)", -1e6, 1e6);
    joint.compliance.form = form;
    joint.compliance.cubic.coefficients = {k[0], k[1], k[2], k[3]};
    joint.depth_min_m = range[0];
    joint.depth_max_m = range[1];
    joint.backlash_rad = backlash[j];
  }
  Optional(r, t, p, "backlash_centre_rad", out.backlash_centre_rad, "rad", -0.05, 0.05);
  Optional(r, t, p, "initial_shaft_offset_rad", out.initial_shaft_offset_rad, "rad", -0.05, 0.05);
  for (int j = 0; j < 2; ++j) {
    if (std::abs(out.initial_shaft_offset_rad[j]) >= backlash[j]) {
      r.Fail(p + "/initial_shaft_offset_rad",
             "joint " + std::to_string(j + 1) + "'s shaft starts at or beyond its wall",
             "give an offset inside the clearance, |offset| < backlash_rad");
    }
  }
  if (t.contains("bias_torque")) {
    const json& b = t["bias_torque"];
    const std::string pb = p + "/bias_torque";
    r.Object(b, pb,
             {{"joint1", false},
              {"joint2", false},
              {"depth_slope_nm_per_m", false},
              {"reference_depth_m", false}});
    if (b.contains("joint1")) out.joints[0].bias_torque = ReadTable(r, b["joint1"], pb + "/joint1");
    if (b.contains("joint2")) out.joints[1].bias_torque = ReadTable(r, b["joint2"], pb + "/joint2");
    Optional(r, b, pb, "depth_slope_nm_per_m", out.bias_depth_slope_nm_per_m, "N·m/m", -10, 10);
    Optional(r, b, pb, "reference_depth_m", out.bias_reference_depth_m, "m", 0, 0.3);
  }
  models::ModelParameters check;
  check.joints = out.joints;
  const std::string why = models::ValidateParameters(check);
  if (!why.empty()) {
    r.Fail(why.find("bias_torque") != std::string::npos ? p + "/bias_torque" : pc,
           "the truth is not a usable instrument: " + why,
           "give a compliance law that stays positive over depth_range_m and well-formed tables");
  }
}

void ReadDynamics(const ScenarioReader& r, const json& doc, Scenario& s) {
  if (doc.contains("joint")) {
    r.Object(doc["joint"], "/joint", {{"inertia_kg_m2", true}});
    Optional(r, doc["joint"], "/joint", "inertia_kg_m2", s.joint.inertia_kg_m2, "kg·m²", 1e-4, 10);
  }
  if (doc.contains("tip")) {
    const json& t = doc["tip"];
    r.Object(t, "/tip",
             {{"inertia_kg_m2", false},
              {"damping_nm_s_per_rad", false},
              {"shaft_damping_nm_s_per_rad", false}});
    Optional(r, t, "/tip", "inertia_kg_m2", s.tip.inertia_kg_m2, "kg·m²", 1e-8, 1e-2);
    Optional(r, t, "/tip", "damping_nm_s_per_rad", s.tip.damping_nm_s_per_rad, "N·m·s/rad", 1e-7,
             1);
    Optional(r, t, "/tip", "shaft_damping_nm_s_per_rad", s.tip.shaft_damping_nm_s_per_rad,
             "N·m·s/rad", 0, 10);
  }
  if (doc.contains("controller")) {
    const json& c = doc["controller"];
    const std::string p = "/controller";
    auto& out = s.controller;
    r.Object(c, p,
             {{"rate_hz", false},
              {"kp_nm_per_rad", false},
              {"ki_nm_per_rad_s", false},
              {"kd_nm_s_per_rad", false},
              {"effort_limit_nm", false},
              {"integral_limit_nm", false},
              {"velocity_filter_hz", false}});
    Optional(r, c, p, "rate_hz", out.rate_hz, "Hz", 50, 20000);
    Optional(r, c, p, "kp_nm_per_rad", out.kp_nm_per_rad, "N·m/rad", 0, 1e4);
    Optional(r, c, p, "ki_nm_per_rad_s", out.ki_nm_per_rad_s, "N·m/(rad·s)", 0, 1e4);
    Optional(r, c, p, "kd_nm_s_per_rad", out.kd_nm_s_per_rad, "N·m·s/rad", 0, 1e3);
    Optional(r, c, p, "effort_limit_nm", out.effort_limit_nm, "N·m", 0.1, 10);
    Optional(r, c, p, "integral_limit_nm", out.integral_limit_nm, "N·m", 0, 10);
    Optional(r, c, p, "velocity_filter_hz", out.velocity_filter_hz, "Hz", 1, 1e4);
  }
}

void ReadSensors(const ScenarioReader& r, const json& c, SensorSettings& out) {
  const std::string p = "/sensors";
  r.Object(c, p,
           {{"encoder_count_rad", false},
            {"depth_count_m", false},
            {"effort_noise_sd_nm", false},
            {"effort_count_nm", false},
            {"effort_delay_s", false},
            {"tracker", false},
            {"tracker_noise_sd_rad", false}});
  Optional(r, c, p, "encoder_count_rad", out.encoder_count_rad, "rad", 0, 1e-2);
  Optional(r, c, p, "depth_count_m", out.depth_count_m, "m", 0, 1e-2);
  Optional(r, c, p, "effort_noise_sd_nm", out.effort_noise_sd_nm, "N·m", 0, 1);
  Optional(r, c, p, "effort_count_nm", out.effort_count_nm, "N·m", 0, 0.1);
  Optional(r, c, p, "effort_delay_s", out.effort_delay_s, "s", 0, 1);
  Optional(r, c, p, "tracker_noise_sd_rad", out.tracker_noise_sd_rad, "rad", 0, 0.1);
  if (c.contains("tracker")) {
    if (!c["tracker"].is_boolean()) {
      r.Fail(p + "/tracker", "sensors.tracker must be true or false", "write true or false");
    }
    out.tracker = c["tracker"].get<bool>();
  }
}

void ReadHiddenEffects(const ScenarioReader& r, const json& h, std::vector<HiddenEffect>& out) {
  const std::string p = "/hidden_effects";
  if (!h.is_object()) r.Fail(p, "hidden_effects must be an object", "write { \"name\": {...} }");
  const auto& catalogue = estimation::EffectCatalogue::Global();
  for (const auto& item : h.items()) {
    const std::string pe = ScenarioReader::Child(p, item.key());
    for (const char* truth : {"bias_torque", "compliance", "backlash_sign", "backlash_deadzone"}) {
      if (item.key() == truth) {
        r.Fail(pe, "'" + item.key() + "' is part of the truth, not a hidden effect",
               "size it under \"truth\" (backlash is the simulator's real clearance)");
      }
    }
    if (!catalogue.Contains(item.key())) {
      std::string known;
      for (const auto& name : catalogue.Names()) known += (known.empty() ? "" : ", ") + name;
      r.Fail(pe, "no effect named '" + item.key() + "' in the catalogue; known: " + known,
             "correct the name or register your effect before simulating");
    }
    const auto specs = catalogue.Create(item.key())->Parameters();
    std::vector<Key> keys;
    for (const auto& spec : specs) keys.push_back({spec.name.c_str(), false});
    r.Object(item.value(), pe, keys);
    HiddenEffect effect{item.key(), {}};
    for (const auto& spec : specs) {
      if (!item.value().contains(spec.name)) continue;
      effect.parameters[spec.name] =
          r.Number(item.value()[spec.name], ScenarioReader::Child(pe, spec.name), spec.unit.c_str(),
                   spec.lower_bound, spec.upper_bound);
    }
    out.push_back(std::move(effect));
  }
}

void ReadLogAndIntegrator(const ScenarioReader& r, const json& doc, Scenario& s) {
  if (doc.contains("log")) {
    const json& l = doc["log"];
    r.Object(l, "/log", {{"mode", false}, {"every_n_periods", false}});
    if (l.contains("mode")) {
      const std::string mode = r.String(l["mode"], "/log/mode");
      if (mode == "all") {
        s.log.mode = LogMode::kAll;
      } else if (mode == "holds") {
        s.log.mode = LogMode::kHolds;
      } else if (mode == "hold_means") {
        s.log.mode = LogMode::kHoldMeans;
      } else {
        r.Fail("/log/mode", "unknown log mode '" + mode + "'", "use all, holds or hold_means");
      }
    }
    if (l.contains("every_n_periods")) {
      s.log.every_n_periods = r.Integer(l["every_n_periods"], "/log/every_n_periods", 1, 100000);
    }
  }
  if (doc.contains("integrator")) {
    const json& i = doc["integrator"];
    const std::string p = "/integrator";
    r.Object(i, p,
             {{"relative_tolerance", false},
              {"angle_tolerance_rad", false},
              {"velocity_tolerance_rad_s", false}});
    auto& out = s.integrator;
    Optional(r, i, p, "relative_tolerance", out.relative_tolerance, "", 1e-12, 1e-2);
    Optional(r, i, p, "angle_tolerance_rad", out.angle_tolerance_rad, "rad", 1e-15, 1e-4);
    Optional(r, i, p, "velocity_tolerance_rad_s", out.velocity_tolerance_rad_s, "rad/s", 1e-15, 1);
  }
}

// "experiment.depths_m=[0.1,0.2]" -> pointer and JSON value; bare words are strings.
std::vector<Override> ApplyOverrides(json& doc, const std::vector<std::string>& overrides) {
  std::vector<Override> applied;
  for (const std::string& text : overrides) {
    const std::size_t eq = text.find('=');
    if (eq == std::string::npos || eq == 0) {
      throw io::InputError("--set " + text, 0, 0, "an override must be key=value",
                           "write e.g. --set experiment.depths_m=[0.1,0.2]");
    }
    // Walk the dotted key through objects only: a number taken as an array
    // index would let "--set a.99999999999=1" grow an array without bound
    // (found by fuzzing).
    std::string pointer;
    json* node = &doc;
    std::stringstream keys(text.substr(0, eq));
    for (std::string key; std::getline(keys, key, '.');) {
      if (node->is_null()) *node = json::object();  // a section the file leaves out
      if (!node->is_object()) {
        throw io::InputError("--set " + text, 0, 0,
                             "cannot set " + text.substr(0, eq) + ": " +
                                 io::DottedJsonPointer(pointer, "the scenario") +
                                 " is not an object",
                             "name a key inside an object of the scenario");
      }
      pointer += "/" + io::JsonPointerToken(key);
      node = &(*node)[key];
    }
    const std::string value_text = text.substr(eq + 1);
    json value = json::parse(value_text, nullptr, false);
    if (value.is_discarded()) value = value_text;
    *node = value;
    applied.push_back({pointer, text});
  }
  return applied;
}

}  // namespace
}  // namespace detail

Scenario ParseScenario(const std::string& text, const std::string& file,
                       const std::vector<std::string>& overrides) {
  using detail::json;
  json doc = io::ParseJsonInput(text, file);
  if (!doc.is_object()) {
    throw io::InputError(file, 1, 1, "a scenario must be a JSON object", "see docs/simulator.md");
  }
  const auto applied = detail::ApplyOverrides(doc, overrides);
  const detail::ScenarioReader r(text, file, applied);
  r.Object(doc, "",
           {{"format", true},
            {"version", true},
            {"description", true},
            {"experiment", true},
            {"truth", true},
            {"joint", false},
            {"tip", false},
            {"controller", false},
            {"sensors", false},
            {"hidden_effects", false},
            {"log", false},
            {"integrator", false}});
  if (r.String(doc["format"], "/format") != detail::kFormat) {
    r.Fail("/format", "format must be \"pliant-scenario\"", "is this a scenario file?");
  }
  r.Integer(doc["version"], "/version", 1, 1);
  Scenario s;
  const std::size_t slash = file.find_last_of('/');
  s.name = file.substr(slash == std::string::npos ? 0 : slash + 1);
  s.name = s.name.substr(0, s.name.rfind(".json"));
  s.description = r.String(doc["description"], "/description");
  s.truth = DefaultTruth();
  detail::ReadTruth(r, doc["truth"], s.truth);
  detail::ReadExperiment(r, doc["experiment"], s);
  detail::ReadDynamics(r, doc, s);
  if (doc.contains("sensors")) detail::ReadSensors(r, doc["sensors"], s.sensors);
  if (doc.contains("hidden_effects")) {
    detail::ReadHiddenEffects(r, doc["hidden_effects"], s.hidden_effects);
  }
  detail::ReadLogAndIntegrator(r, doc, s);
  return s;
}

Scenario ReadScenario(const std::string& path, const std::vector<std::string>& overrides) {
  std::ifstream in(path, std::ios::binary);
  if (!in) {
    throw io::InputError(path, 0, 0, "cannot open the scenario file",
                         "check the path (scenarios live in experiments/scenarios/)");
  }
  std::ostringstream text;
  text << in.rdbuf();
  return ParseScenario(text.str(), path, overrides);
}

}  // namespace pliant::experiments
