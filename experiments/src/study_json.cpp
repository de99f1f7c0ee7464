// Study files (docs/montecarlo.md): checked with the scenario reader's tools,
// so every problem is an InputError at the line of the key that is wrong.
#include <filesystem>
#include <fstream>
#include <sstream>

#include "pliant/experiments/study.h"
#include "pliant/io/json_input.h"
#include "scenario_reader.h"

namespace pliant::experiments {
namespace {

using detail::json;
using detail::ScenarioReader;

constexpr const char* kFormat = "pliant-study";

struct QuantitySpec {
  const char* section;
  const char* key;
  int first;   ///< SampledQuantity (two consecutive ones for a per-joint key)
  bool per_joint;
  const char* unit;
  double lower, upper;  ///< every draw is clamped to this range
};

// Where each sampled quantity lives in the file, and its physical range.
constexpr QuantitySpec kSpecs[] = {
    {"instrument", "compliance_scale", kComplianceScale1, true, "(× nominal K)", 0.2, 5.0},
    {"instrument", "backlash_rad", kBacklash1Rad, true, "rad", 0.0, 0.05},
    {"instrument", "bias_offset_nm", kBiasOffset1Nm, true, "N·m", -1.0, 1.0},
    {"noise", "effort_sd_nm", kEffortNoiseSdNm, false, "N·m", 0.0, 0.5},
    {"contact", "depth_m", kDepthM, false, "m", 0.0, 0.3},
    {"contact", "direction_deg", kDirectionDeg, false, "deg", -360.0, 360.0},
    {"contact", "peak_torque_nm", kPeakTorqueNm, false, "N·m", 0.01, 3.0},
    {"contact", "speed_rad_s", kSpeedRadS, false, "rad/s", 1e-4, 2.0},
    {"instrument", "shaft_start", kShaftStart1, true, "(share of the clearance)", -1.0, 1.0},
};

// A bare number (constant) or {"uniform": [min, max]}, {"normal": [mean, sd]},
// {"lognormal": [median, sd_log]}.
Distribution ReadDistribution(const ScenarioReader& r, const json& v, const std::string& p,
                              const QuantitySpec& spec) {
  Distribution d;
  if (v.is_number()) {
    d.a = r.Number(v, p, spec.unit, spec.lower, spec.upper);
    return d;
  }
  r.Object(v, p, {{"uniform", false}, {"normal", false}, {"lognormal", false}});
  if (v.size() != 1) {
    r.Fail(p, r.Dotted(p) + " must name one distribution, found " + std::to_string(v.size()),
           "write a number, {\"uniform\": [min, max]}, {\"normal\": [mean, sd]} or "
           "{\"lognormal\": [median, sd_log]}");
  }
  const std::string kind = v.begin().key();
  const std::string pk = p + "/" + kind;
  if (kind == "uniform") {
    const auto x = r.Pair(v[kind], pk, spec.unit, spec.lower, spec.upper);
    if (!(x[0] <= x[1])) r.Fail(pk, r.Dotted(pk) + ": min > max", "write [min, max]");
    d = {Distribution::Kind::kUniform, x[0], x[1]};
  } else if (kind == "normal") {
    r.Pair(v[kind], pk, spec.unit, -1e6, 1e6);
    const double mean = r.Number(v[kind][0], pk + "/0", spec.unit, spec.lower, spec.upper);
    const double sd = r.Number(v[kind][1], pk + "/1", spec.unit, 0.0, spec.upper - spec.lower);
    d = {Distribution::Kind::kNormal, mean, sd};
  } else {
    r.Pair(v[kind], pk, "", -1e6, 1e6);
    const double median = r.Number(v[kind][0], pk + "/0", spec.unit, 1e-9, spec.upper);
    const double sd_log = r.Number(v[kind][1], pk + "/1", "(of the log)", 0.0, 2.0);
    if (spec.lower < 0.0) r.Fail(pk, r.Dotted(p) + " can be negative", "use uniform or normal");
    d = {Distribution::Kind::kLogNormal, median, sd_log};
  }
  d.lower = spec.lower;
  d.upper = spec.upper;
  return d;
}

std::vector<std::string> ReadSet(const ScenarioReader& r, const json& v, const std::string& p) {
  if (!v.is_array()) {
    r.Fail(p, r.Dotted(p) + " must be an array of \"key=value\" strings",
           "write e.g. [\"experiment.hold_s=0.5\"]");
  }
  std::vector<std::string> out;
  for (std::size_t i = 0; i < v.size(); ++i) out.push_back(r.String(v[i], p + "/" + std::to_string(i)));
  return out;
}

std::uint64_t Fnv1a(const std::string& text, std::uint64_t hash = 0xcbf29ce484222325ull) {
  for (unsigned char c : text) hash = (hash ^ c) * 0x100000001b3ull;
  return hash;
}

std::string ReadText(const std::string& path, const char* what, const char* fix) {
  // Only regular files of sane size: a path to /dev/zero or a FIFO would never end.
  std::error_code error;
  if (!std::filesystem::exists(path, error)) {
    throw io::InputError(path, 0, 0, std::string("no such ") + what, fix);
  }
  if (!std::filesystem::is_regular_file(path, error) ||
      std::filesystem::file_size(path, error) > (16u << 20)) {
    throw io::InputError(path, 0, 0, std::string("the ") + what + " is not a regular file under 16 MB", fix);
  }
  std::ifstream in(path, std::ios::binary);
  if (!in) throw io::InputError(path, 0, 0, std::string("cannot open the ") + what, fix);
  std::ostringstream text;
  text << in.rdbuf();
  return text.str();
}

// The study file's word for each identification method.
const char* IdentifyMethodName(Study::IdentifyMethod method) {
  return method == Study::IdentifyMethod::kPaper ? "paper" : "smoother";
}

}  // namespace

Study ParseStudy(const std::string& text, const std::string& file) {
  json doc = io::ParseJsonInput(text, file);
  if (!doc.is_object()) {
    throw io::InputError(file, 1, 1, "a study must be a JSON object", "see docs/montecarlo.md");
  }
  const ScenarioReader r(text, file, {}, "the study", " (docs/montecarlo.md shows a complete study)");
  r.Object(doc, "",
           {{"format", true}, {"version", true}, {"description", true}, {"scenario", true},
            {"scenario_set", false}, {"trials", true}, {"seed", true}, {"identify", false},
            {"identify_method", false},
            {"calibration", false}, {"arm_calibration", false}, {"instrument", false}, {"noise", false},
            {"contact", false}, {"filter", false}});
  if (r.String(doc["format"], "/format") != kFormat) {
    r.Fail("/format", "format must be \"pliant-study\"", "is this a study file?");
  }
  r.Integer(doc["version"], "/version", 1, 1);
  Study s;
  const std::filesystem::path path(file);
  s.name = path.stem().string();
  s.description = r.String(doc["description"], "/description");
  s.trials = r.Integer(doc["trials"], "/trials", 1, 100000000);
  s.seed = static_cast<std::uint64_t>(r.Integer(doc["seed"], "/seed", 0, 2147483647));
  if (doc.contains("identify")) {
    if (!doc["identify"].is_boolean()) {
      r.Fail("/identify", "identify must be true or false, found " + doc["identify"].dump(),
             "write true (identify on a simulated calibration) or false (nominal parameters)");
    }
    s.identify = doc["identify"].get<bool>();
  }
  if (doc.contains("identify_method")) {
    const std::string method = r.String(doc["identify_method"], "/identify_method");
    if (method != IdentifyMethodName(Study::IdentifyMethod::kSmoother) &&
        method != IdentifyMethodName(Study::IdentifyMethod::kPaper)) {
      r.Fail("/identify_method", "identify_method must be \"smoother\" or \"paper\", found \"" + method + "\"",
             "write \"smoother\" (what pliant identify runs on timed logs) or \"paper\" (the paper's procedure)");
    }
    s.identify_method = method == IdentifyMethodName(Study::IdentifyMethod::kPaper)
                            ? Study::IdentifyMethod::kPaper
                            : Study::IdentifyMethod::kSmoother;
  }
  if (doc.contains("filter")) {  // the estimator's own options, not the plant's
    const auto& filter = doc["filter"];
    r.Object(filter, "/filter",
             {{"deflection_model_error", false}, {"load_follows_motor", false}, {"infer_contact", false},
              {"tip_fixed_hint", false}, {"inertial_torque_error", false}, {"unloaded_start_s", false},
              {"internal_inertia_sd_kg_m2", false}, {"internal_coulomb_sd_nm", false},
              {"internal_viscous_sd_nm_s", false}});
    if (filter.contains("deflection_model_error")) {
      s.deflection_model_error = r.Number(filter["deflection_model_error"],
                                          "/filter/deflection_model_error", "(share of K·τ)", 0.0, 1.0);
    }
    const auto flag = [&](const char* key, const std::string& advice, bool* value) {
      if (!filter.contains(key)) return;
      if (!filter[key].is_boolean()) {
        r.Fail(std::string("/filter/") + key,
               std::string(key) + " must be true or false, found " + filter[key].dump(), advice);
      }
      *value = filter[key].get<bool>();
    };
    flag("load_follows_motor", "write true (a held load follows the motor) or false (a random walk)",
         &s.load_follows_motor);
    flag("infer_contact",
         "write true (contact is the exception where tip_fixed is 0) or false (all effort is load)",
         &s.infer_contact);
    flag("tip_fixed_hint",
         "write true (the filter reads the log's tip_fixed) or false (it is not told: online)",
         &s.tip_fixed_hint);
    if (filter.contains("inertial_torque_error")) {
      s.inertial_torque_error = r.Number(filter["inertial_torque_error"],
                                         "/filter/inertial_torque_error", "(share of J·θ̈)", 0.0, 10.0);
    }
    if (filter.contains("unloaded_start_s")) {
      s.unloaded_start_s =
          r.Number(filter["unloaded_start_s"], "/filter/unloaded_start_s", "s", 0.0, 60.0);
    }
    const auto prior = [&](const char* key, const char* unit, double* value) {
      if (!filter.contains(key)) return;
      *value = r.Number(filter[key], std::string("/filter/") + key, unit, 0.0, 10.0);
    };
    prior("internal_inertia_sd_kg_m2", "kg·m²", &s.internal_inertia_sd_kg_m2);
    prior("internal_coulomb_sd_nm", "N·m", &s.internal_coulomb_sd_nm);
    prior("internal_viscous_sd_nm_s", "N·m·s/rad", &s.internal_viscous_sd_nm_s);
  }
  if (doc.contains("scenario_set")) s.scenario_set = ReadSet(r, doc["scenario_set"], "/scenario_set");
  // The scenario: a path relative to the study file, its overrides applied.
  const std::string scenario = r.String(doc["scenario"], "/scenario");
  s.scenario_path = (path.parent_path() / scenario).lexically_normal().string();
  std::string scenario_text;
  try {
    scenario_text = ReadText(s.scenario_path, "scenario file", "check the path");
    s.scenario = ParseScenario(scenario_text, s.scenario_path, s.scenario_set);
  } catch (const io::InputError& e) {
    r.Fail(doc.contains("scenario_set") ? "/scenario_set" : "/scenario",
           "the study's scenario is not usable: " + std::string(e.what()),
           "fix the scenario file or scenario_set");
  }
  std::string calibration_texts;
  // One {"scenario": FILE, "set": [...]} entry, read into `into`.
  const auto read_entry = [&](const json& entry, const std::string& pc, std::vector<Scenario>* into) {
    r.Object(entry, pc, {{"scenario", true}, {"set", false}});
    const std::string calibration_path =
        (path.parent_path() / r.String(entry["scenario"], pc + "/scenario")).lexically_normal().string();
    const auto set = entry.contains("set") ? ReadSet(r, entry["set"], pc + "/set") : std::vector<std::string>{};
    try {
      const std::string calibration_text = ReadText(calibration_path, "scenario file", "check the path");
      into->push_back(ParseScenario(calibration_text, calibration_path, set));
      calibration_texts += calibration_text;
    } catch (const io::InputError& e) {
      r.Fail(pc, "this calibration scenario is not usable: " + std::string(e.what()),
             "fix the scenario file or the set");
    }
  };
  if (doc.contains("calibration")) {
    const json& c = doc["calibration"];
    if (!c.is_array()) {
      r.Fail("/calibration", "calibration must be an array of {\"scenario\": FILE, \"set\": [...]}",
             "see experiments/studies/identify_study.json");
    }
    for (std::size_t i = 0; i < c.size(); ++i)
      read_entry(c[i], "/calibration/" + std::to_string(i), &s.calibration);
  }
  if (doc.contains("arm_calibration")) {
    read_entry(doc["arm_calibration"], "/arm_calibration", &s.arm_calibration);
    if (s.arm_calibration.back().type != ExperimentType::kFreeMotion) {
      r.Fail("/arm_calibration", "the arm's calibration must be a free_motion experiment",
             "use experiments/scenarios/free_motion.json, or a copy of it");
    }
  }
  if (s.identify && s.calibration.empty()) {
    r.Fail("/identify", "identify is true but the study has no calibration",
           "add \"calibration\": [{\"scenario\": \"../scenarios/clamped_beam.json\"}] or set identify to false");
  }
  const bool clamped = s.scenario.type == ExperimentType::kClampedBeam;
  if (s.scenario.type != ExperimentType::kDivot && !clamped) {
    r.Fail("/scenario", "the scenario must be a divot or clamped_beam experiment",
           "use experiments/scenarios/divot.json or clamped_beam.json, or a copy of one");
  }
  if (clamped && s.scenario.log.mode != LogMode::kAll) {
    r.Fail("/scenario_set", "a clamped-beam study needs every sample in the log (the filter runs on them)",
           "add \"log.mode=all\" to scenario_set");
  }
  // Defaults: the scenario's own instrument, noise and first contact.
  const Scenario& base = s.scenario;
  for (int j = 0; j < 2; ++j) {
    s.quantities[kComplianceScale1 + j].a = 1.0;
    s.quantities[kBacklash1Rad + j].a = base.truth.joints[j].backlash_rad;
    const double clearance = base.truth.joints[j].backlash_rad;
    s.quantities[kShaftStart1 + j].a =
        clearance > 0.0 ? base.truth.initial_shaft_offset_rad[j] / clearance : 0.0;
  }
  s.quantities[kEffortNoiseSdNm].a = base.sensors.effort_noise_sd_nm;
  if (clamped) {  // a sweep at one depth up to an effort limit: no direction, no speed
    s.quantities[kDepthM].a = base.clamped_beam.depths_m.front();
    s.quantities[kPeakTorqueNm].a = base.clamped_beam.effort_limit_nm;
  } else {
    s.quantities[kDepthM].a = base.divot.depths_m.front();
    s.quantities[kDirectionDeg].a = base.divot.directions_deg.front();
    s.quantities[kPeakTorqueNm].a = base.divot.peak_torques_nm.front();
    s.quantities[kSpeedRadS].a = base.divot.speeds_rad_s.front();
  }
  for (const char* section : {"instrument", "noise", "contact"}) {
    if (!doc.contains(section)) continue;
    std::vector<io::JsonKey> keys;
    for (const auto& spec : kSpecs) {
      if (std::string(spec.section) == section) keys.push_back({spec.key, false});
    }
    const std::string ps = std::string("/") + section;
    r.Object(doc[section], ps, keys);
    for (const auto& spec : kSpecs) {
      if (std::string(spec.section) != section || !doc[section].contains(spec.key)) continue;
      QuantitySpec checked = spec;
      if (clamped && (spec.first == kDirectionDeg || spec.first == kSpeedRadS)) {
        r.Fail(ps + "/" + spec.key, std::string("a clamped-beam sweep has no ") + spec.key,
               "remove it (the sweep steps the tip until |effort| reaches peak_torque_nm)");
      }
      if (clamped && spec.first == kPeakTorqueNm) checked.lower = 0.05;  // the protocol's limit
      if (spec.first == kDepthM) {  // pushes only where the truth's law is valid
        checked.lower = base.truth.joints[0].depth_min_m;
        checked.upper = base.truth.joints[0].depth_max_m;
      }
      const json& value = doc[section][spec.key];
      const std::string pk = ps + "/" + spec.key;
      // [joint 1's, joint 2's]: an instrument's joints differ (their nominal clearances do).
      if (spec.per_joint && value.is_array()) {
        if (value.size() != 2) {
          r.Fail(pk, r.Dotted(pk) + " must hold two distributions (joint 1, joint 2), found " +
                         std::to_string(value.size()),
                 "write [joint 1's, joint 2's], or one distribution for both joints");
        }
        for (int j = 0; j < 2; ++j) {
          s.quantities[spec.first + j] =
              ReadDistribution(r, value[j], pk + "/" + std::to_string(j), checked);
        }
        continue;
      }
      const auto d = ReadDistribution(r, value, pk, checked);
      s.quantities[spec.first] = d;
      if (spec.per_joint) s.quantities[spec.first + 1] = d;
    }
  }
  doc.erase("trials");  // more trials extend a study; they do not make another one
  // The method as read, not as written: a default that changes makes another study.
  if (s.identify) doc["identify_method"] = IdentifyMethodName(s.identify_method);
  s.fingerprint = Fnv1a(calibration_texts, Fnv1a(scenario_text, Fnv1a(doc.dump() + "\n")));
  s.arm_effects = IdentifyArmDynamics(s);
  return s;
}

Study ReadStudy(const std::string& path) {
  return ParseStudy(ReadText(path, "study file", "check the path (examples: experiments/studies/)"),
                    path);
}

}  // namespace pliant::experiments
