// The loop of the simulator: the protocol's phases, sampled and controlled at
// the controller rate, the plant integrated by CVODE between samples.
#include "pliant/experiments/simulator.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <string>

#include "controller_and_sensors.h"
#include "protocols.h"
#include "psm_plant.h"

namespace pliant::experiments {
namespace {

// Rounded for storage so that the log stays small: far below the encoder
// count (angles), the current ADC step (efforts) and the period (time).
// Dividing by an exact power of ten gives the double nearest the rounded
// decimal, which the writer prints in its shortest form.
double Round(double value, double scale) { return std::round(value * scale) / scale; }

class LogBuilder {
 public:
  LogBuilder(const Scenario& scenario, std::uint64_t seed) : tracker_(scenario.sensors.tracker) {
    auto& h = log_.header;
    h.columns = {"t", "q1", "q2", "q3", "tau1", "tau2", "v1", "v2", "q1_cmd", "q2_cmd", "q3_cmd"};
    if (tracker_) h.columns.insert(h.columns.end(), {"q1_ref", "q2_ref"});
    h.columns.insert(h.columns.end(), {"q1_true", "q2_true", "tip_fixed", "segment"});
    char text[256];
    std::snprintf(text, sizeof text, "%s (%s)", scenario.name.c_str(),
                  ExperimentName(scenario.type));
    h.metadata = {{"generator", "pliant simulate (CVODE BDF, docs/simulator.md)"},
                  {"scenario", text},
                  {"seed", std::to_string(seed)},
                  {"arm", "PSM joints 1-2 (simulated)"},
                  {"units", "SI: rad, m, N·m, s"}};
    const auto& t = scenario.truth;
    std::snprintf(text, sizeof text, "backlash %.6g %.6g rad, clearance centre %.6g %.6g rad",
                  t.joints[0].backlash_rad, t.joints[1].backlash_rad, t.backlash_centre_rad[0],
                  t.backlash_centre_rad[1]);
    h.metadata.emplace_back("truth", text);
    std::string hidden;
    for (const auto& effect : scenario.hidden_effects) {
      hidden += (hidden.empty() ? "" : "; ") + effect.name;
      for (const auto& [name, value] : effect.parameters) {
        std::snprintf(text, sizeof text, " %s=%.6g", name.c_str(), value);
        hidden += text;
      }
    }
    h.metadata.emplace_back("hidden effects", hidden.empty() ? "none" : hidden);
    row_.resize(h.columns.size());
  }

  // One sample, in column order.
  std::vector<double>& Row(double t, const Eigen::Vector2d& q, double q3,
                           const Eigen::Vector2d& tau, const Eigen::Vector2d& v,
                           const Eigen::Vector3d& command, const Eigen::Vector2d* reference,
                           const Eigen::Vector2d& truth, bool tip_fixed, int segment) {
    std::size_t c = 0;
    auto put = [&](double value, double scale) { row_[c++] = Round(value, scale); };
    put(t, 1e9);
    put(q[0], 1e10), put(q[1], 1e10), put(q3, 1e10);
    put(tau[0], 1e9), put(tau[1], 1e9);
    put(v[0], 1e9), put(v[1], 1e9);
    put(command[0], 1e10), put(command[1], 1e10), put(command[2], 1e10);
    if (reference) put((*reference)[0], 1e10), put((*reference)[1], 1e10);
    put(truth[0], 1e10), put(truth[1], 1e10);
    row_[c++] = tip_fixed ? 1.0 : 0.0;
    row_[c++] = segment;
    return row_;
  }

  void Append(const std::vector<double>& row) {
    log_.values.insert(log_.values.end(), row.begin(), row.end());
  }

  io::Log& log() { return log_; }

 private:
  bool tracker_;
  io::Log log_;
  std::vector<double> row_;
};

}  // namespace

SimulationResult Simulate(const Scenario& scenario, std::uint64_t seed) {
  const double period_s = 1.0 / scenario.controller.rate_hz;
  const TruthModel truth(scenario);
  auto protocol = detail::MakeProtocol(scenario, period_s);
  detail::Phase phase;
  if (!protocol->Next(nullptr, &phase)) return {};
  const Eigen::Vector3d start = phase.command(0.0);

  detail::PsmPlant plant(scenario, truth, start.head<2>(), start[2]);
  models::JointState<double> initial;
  initial.encoder_angle_rad = start.head<2>();
  initial.insertion_depth_m = start[2];
  detail::Sensors sensors(scenario.sensors, period_s, seed);
  // The integral term starts at the bias torque: the arm is at rest, holding.
  detail::PidController pid(scenario.controller, start.head<2>(), sensors.Encoder(start.head<2>()),
                            truth.InternalTorque(initial));
  LogBuilder builder(scenario, seed);
  SimulationResult result;
  const LogMode mode = scenario.log.mode;
  const int every = scenario.log.every_n_periods;
  long k = 0;
  std::vector<double> sum;
  do {
    plant.SetTipFixed(phase.tip_fixed);
    const long n =
        std::max({1L, long(phase.hold_samples), std::lround(phase.duration_s / period_s)});
    const long hold_from = n - phase.hold_samples;
    sum.assign(builder.log().header.columns.size(), 0.0);
    HoldRecord hold;
    for (long i = 0; i < n; ++i, ++k) {
      const double t = k * period_s;
      const Eigen::Vector3d command = phase.command(i * period_s);
      const Eigen::Vector2d encoder = sensors.Encoder(plant.JointAngle());
      const Eigen::Vector2d effort_out = pid.Update(command.head<2>(), encoder);
      const Eigen::Vector2d effort = sensors.Effort(effort_out);
      const Eigen::Vector2d tip = plant.TipAngle();
      Eigen::Vector2d reference;
      if (scenario.sensors.tracker) reference = sensors.Tracker(tip);
      const auto& row = builder.Row(
          t, encoder, sensors.Depth(command[2]), effort, pid.velocity_rad_s(), command,
          scenario.sensors.tracker ? &reference : nullptr, tip, phase.tip_fixed, phase.segment);
      const bool in_hold = i >= hold_from;
      if (mode == LogMode::kAll ? k % every == 0 : (mode == LogMode::kHolds && in_hold)) {
        builder.Append(row);
      }
      if (in_hold) {
        for (std::size_t c = 0; c < row.size(); ++c) sum[c] += row[c];
        hold.encoder_rad += encoder;
        hold.effort_nm += effort;
        hold.true_angle_rad += tip;
        hold.command_rad += command.head<2>();
        if (i == n - 1) {
          const double count = double(phase.hold_samples);
          hold = {phase.segment,
                  t,
                  command[2],
                  phase.tip_fixed,
                  hold.encoder_rad / count,
                  hold.effort_nm / count,
                  hold.true_angle_rad / count,
                  hold.command_rad / count};
          result.holds.push_back(hold);
          if (mode == LogMode::kHoldMeans) {
            for (double& value : sum) value /= count;
            sum[0] = row[0];  // the time of the hold's last sample
            builder.Append(sum);
          }
        }
      }
      plant.SetInput(effort_out, command[2]);
      plant.Advance((k + 1) * period_s);
    }
  } while (protocol->Next(result.holds.empty() ? nullptr : &result.holds.back(), &phase));

  result.segments = protocol->segments();
  for (const auto& segment : result.segments) {
    builder.log().header.metadata.emplace_back("segment " + std::to_string(segment.id),
                                               segment.label);
  }
  result.log = std::move(builder.log());
  result.stats = plant.stats();
  result.stats.controller_periods = k;
  return result;
}

}  // namespace pliant::experiments
