// The "experiment" section of a scenario: one protocol per experiment type.
#include "scenario_json_parts.h"

namespace pliant::experiments::detail {
namespace {

// Every depth must lie where the truth's K(L) is defined: the simulator will
// not invent a compliance the scenario did not give.
void CheckDepths(const ScenarioReader& r, const std::vector<double>& depths,
                 const std::string& pointer, const Truth& truth) {
  for (std::size_t i = 0; i < depths.size(); ++i) {
    for (const auto& joint : truth.joints) {
      if (depths[i] < joint.depth_min_m || depths[i] > joint.depth_max_m) {
        r.Fail(pointer + "/" + std::to_string(i),
               "depth " + ScenarioReader::Text(depths[i]) +
                   " m is outside the truth's compliance range [" +
                   ScenarioReader::Text(joint.depth_min_m) + ", " +
                   ScenarioReader::Text(joint.depth_max_m) + "] m",
               "use a depth inside truth.compliance.depth_range_m (the paper fitted K(L) on "
               "0.09-0.22 m)");
      }
    }
  }
}

constexpr double kHardwareDepthMax = 0.24;  // dVRK joint 3 range, m

void ReadBiasSweep(const ScenarioReader& r, const json& e, const std::string& p,
                   BiasSweepProtocol& out) {
  r.Object(e, p,
           {{"type", true},
            {"depths_m", true},
            {"step_deg", false},
            {"joint1_range_deg", false},
            {"joint2_range_deg", false},
            {"move_s", false},
            {"settle_s", false},
            {"hold_samples", false}});
  out.depths_m = r.Numbers(e["depths_m"], p + "/depths_m", 0, "m", 0.0, kHardwareDepthMax);
  if (e.contains("step_deg"))
    out.step_deg = r.Number(e["step_deg"], p + "/step_deg", "deg", 0.1, 90);
  for (int j = 0; j < 2; ++j) {
    const std::string key = j == 0 ? "joint1_range_deg" : "joint2_range_deg";
    const double limit = j == 0 ? 91.0 : 53.0;  // ±1.588 rad, ±0.925 rad
    if (!e.contains(key)) continue;
    const auto range = r.Pair(e[key], p + "/" + key, "deg", -limit, limit);
    if (!(range[0] < range[1])) r.Fail(p + "/" + key, key + " must be [lower, upper]", "swap them");
    (j == 0 ? out.joint1_range_deg : out.joint2_range_deg) = {range[0], range[1]};
  }
  if (e.contains("move_s")) out.move_s = r.Number(e["move_s"], p + "/move_s", "s", 0.01, 60);
  if (e.contains("settle_s")) out.settle_s = r.Number(e["settle_s"], p + "/settle_s", "s", 0, 60);
  if (e.contains("hold_samples")) {
    out.hold_samples = r.Integer(e["hold_samples"], p + "/hold_samples", 1, 100000);
  }
}

void ReadClampedBeam(const ScenarioReader& r, const json& e, const std::string& p,
                     ClampedBeamProtocol& out) {
  r.Object(e, p,
           {{"type", true},
            {"depths_m", true},
            {"joints", false},
            {"tip_step_m", false},
            {"effort_limit_nm", false},
            {"clamp_angle_rad", false},
            {"move_s", false},
            {"settle_s", false},
            {"hold_samples", false},
            {"max_steps_per_leg", false}});
  out.depths_m = r.Numbers(e["depths_m"], p + "/depths_m", 0, "m", 0.0, kHardwareDepthMax);
  if (e.contains("joints")) {
    const auto joints = r.Numbers(e["joints"], p + "/joints", 0, "(1 or 2)", 1, 2);
    out.joints.clear();
    for (double j : joints) out.joints.push_back(j < 1.5 ? 1 : 2);
  }
  if (e.contains("tip_step_m")) {
    out.tip_step_m = r.Number(e["tip_step_m"], p + "/tip_step_m", "m", 1e-6, 0.01);
  }
  if (e.contains("effort_limit_nm")) {
    out.effort_limit_nm = r.Number(e["effort_limit_nm"], p + "/effort_limit_nm", "N·m", 0.05, 3.0);
  }
  if (e.contains("clamp_angle_rad")) {
    out.clamp_angle_rad = r.Pair(e["clamp_angle_rad"], p + "/clamp_angle_rad", "rad", -0.9, 0.9);
  }
  if (e.contains("move_s")) out.move_s = r.Number(e["move_s"], p + "/move_s", "s", 0.01, 60);
  if (e.contains("settle_s")) out.settle_s = r.Number(e["settle_s"], p + "/settle_s", "s", 0, 60);
  if (e.contains("hold_samples")) {
    out.hold_samples = r.Integer(e["hold_samples"], p + "/hold_samples", 1, 100000);
  }
  if (e.contains("max_steps_per_leg")) {
    out.max_steps_per_leg = r.Integer(e["max_steps_per_leg"], p + "/max_steps_per_leg", 1, 100000);
  }
}

void ReadDivot(const ScenarioReader& r, const json& e, const std::string& p, DivotProtocol& out) {
  r.Object(e, p,
           {{"type", true},
            {"depths_m", true},
            {"directions_deg", true},
            {"peak_torques_nm", true},
            {"speeds_rad_s", true},
            {"divot_angle_rad", false},
            {"hold_s", false},
            {"rest_s", false}});
  out.depths_m = r.Numbers(e["depths_m"], p + "/depths_m", 0, "m", 0.0, kHardwareDepthMax);
  out.directions_deg = r.Numbers(e["directions_deg"], p + "/directions_deg", 0, "deg", -360, 360);
  out.peak_torques_nm =
      r.Numbers(e["peak_torques_nm"], p + "/peak_torques_nm", 0, "N·m", 0.01, 3.0);
  out.speeds_rad_s = r.Numbers(e["speeds_rad_s"], p + "/speeds_rad_s", 0, "rad/s", 1e-4, 2.0);
  if (e.contains("divot_angle_rad")) {
    out.divot_angle_rad = r.Pair(e["divot_angle_rad"], p + "/divot_angle_rad", "rad", -0.9, 0.9);
  }
  if (e.contains("hold_s")) out.hold_s = r.Number(e["hold_s"], p + "/hold_s", "s", 0, 600);
  if (e.contains("rest_s")) out.rest_s = r.Number(e["rest_s"], p + "/rest_s", "s", 0, 600);
}

void ReadFreeMotion(const ScenarioReader& r, const json& e, const std::string& p,
                    FreeMotionProtocol& out) {
  r.Object(e, p,
           {{"type", true},
            {"duration_s", true},
            {"amplitude_rad", false},
            {"frequency_hz", false},
            {"depth_mid_m", false},
            {"depth_amplitude_m", false},
            {"depth_frequency_hz", false},
            {"ramp_s", false}});
  out.duration_s = r.Number(e["duration_s"], p + "/duration_s", "s", 0.01, 1e5);
  if (e.contains("amplitude_rad")) {
    out.amplitude_rad = r.Pair(e["amplitude_rad"], p + "/amplitude_rad", "rad", 0, 0.9);
  }
  if (e.contains("frequency_hz")) {
    out.frequency_hz = r.Pair(e["frequency_hz"], p + "/frequency_hz", "Hz", 0, 5);
  }
  if (e.contains("depth_mid_m")) {
    out.depth_mid_m = r.Number(e["depth_mid_m"], p + "/depth_mid_m", "m", 0, kHardwareDepthMax);
  }
  if (e.contains("depth_amplitude_m")) {
    out.depth_amplitude_m = r.Number(e["depth_amplitude_m"], p + "/depth_amplitude_m", "m", 0, 0.1);
  }
  if (e.contains("depth_frequency_hz")) {
    out.depth_frequency_hz =
        r.Number(e["depth_frequency_hz"], p + "/depth_frequency_hz", "Hz", 0, 5);
  }
  if (e.contains("ramp_s")) out.ramp_s = r.Number(e["ramp_s"], p + "/ramp_s", "s", 0, 600);
}

}  // namespace

void ReadExperiment(const ScenarioReader& r, const json& e, Scenario& out) {
  const std::string p = "/experiment";
  if (!e.is_object() || !e.contains("type")) {
    r.Fail(p, "experiment must be an object with a \"type\"",
           "write \"experiment\": {\"type\": \"clamped_beam\", ...}");
  }
  const std::string type = r.String(e["type"], p + "/type");
  if (type == "bias_sweep") {
    out.type = ExperimentType::kBiasSweep;
    ReadBiasSweep(r, e, p, out.bias_sweep);
    CheckDepths(r, out.bias_sweep.depths_m, p + "/depths_m", out.truth);
  } else if (type == "clamped_beam") {
    out.type = ExperimentType::kClampedBeam;
    ReadClampedBeam(r, e, p, out.clamped_beam);
    CheckDepths(r, out.clamped_beam.depths_m, p + "/depths_m", out.truth);
  } else if (type == "divot") {
    out.type = ExperimentType::kDivot;
    ReadDivot(r, e, p, out.divot);
    CheckDepths(r, out.divot.depths_m, p + "/depths_m", out.truth);
  } else if (type == "free_motion") {
    out.type = ExperimentType::kFreeMotion;
    ReadFreeMotion(r, e, p, out.free_motion);
    const auto& f = out.free_motion;
    CheckDepths(r, {f.depth_mid_m - f.depth_amplitude_m, f.depth_mid_m + f.depth_amplitude_m},
                p + "/depth_mid_m", out.truth);
  } else {
    r.Fail(p + "/type", "unknown experiment type '" + type + "'",
           "use one of bias_sweep, clamped_beam, divot, free_motion");
  }
}

}  // namespace pliant::experiments::detail
