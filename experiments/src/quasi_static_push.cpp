#include "pliant/experiments/quasi_static_push.h"

#include <algorithm>
#include <cmath>
#include <string>

#include <boost/random/mersenne_twister.hpp>
#include <boost/random/normal_distribution.hpp>

#include "pliant/models/effects/bias_torque.h"
#include "pliant/models/effects/compliance.h"

namespace pliant::experiments {
namespace {

// Load profile of one push at time s since its start: ramp, hold, ramp down.
double LoadFraction(const Push& push, double s) {
  if (s < push.ramp_s) return s / push.ramp_s;
  if (s < push.ramp_s + push.hold_s) return 1.0;
  return std::max(0.0, 1.0 - (s - push.ramp_s - push.hold_s) / push.ramp_s);
}

double Quantise(double value, double step) { return step * std::round(value / step); }

std::vector<double> Flat(const models::ModelParameters& p, bool bias) {
  std::vector<double> out;
  for (const auto& joint : p.joints) {
    if (bias) {
      out.insert(out.end(), joint.bias_torque.torque_nm.begin(), joint.bias_torque.torque_nm.end());
    } else {
      out.insert(out.end(), joint.compliance.cubic.coefficients.begin(),
                 joint.compliance.cubic.coefficients.end());
    }
  }
  return out;
}

}  // namespace

PushScenario DefaultDivotScenario(const models::ModelParameters& truth) {
  PushScenario scenario;
  scenario.truth = truth;
  constexpr double kPi = 3.14159265358979323846;
  for (double depth : {0.12, 0.18}) {
    for (double direction : {0.0, kPi, 0.5 * kPi, 1.5 * kPi, 0.25 * kPi, 1.25 * kPi}) {
      scenario.pushes.push_back({depth, direction, 1.0, 4.0, 2.0});
    }
  }
  return scenario;
}

io::Log GenerateDivotPushLog(const PushScenario& scenario) {
  const auto& truth = scenario.truth;
  const models::BiasTorqueEffect bias(truth.joints[0].bias_torque, truth.joints[1].bias_torque);
  const models::ComplianceEffect compliance(truth.joints[0], truth.joints[1]);
  const std::vector<double> bias_values = Flat(truth, true);
  const std::vector<double> compliance_values = Flat(truth, false);

  io::Log log;
  log.header.metadata = {{"generator", "pliant quasi-static divot push"},
                         {"seed", std::to_string(scenario.seed)},
                         {"arm", "PSM1 (simulated)"},
                         {"units", "SI: rad, m, N·m, s"}};
  log.header.columns = {"t",       "q1",      "q2",        "q3",      "tau1", "tau2", "v1",
                        "v2",      "q1_true", "q2_true",   "tip_fixed", "segment",
                        "motor_temperature_c"};

  boost::random::mt19937_64 rng(scenario.seed);
  boost::random::normal_distribution<double> effort_noise(0.0, scenario.effort_noise_sd_nm);
  const double dt = 1.0 / scenario.sample_rate_hz;
  Eigen::Vector2d shaft_offset = Eigen::Vector2d::Zero();  // place inside the clearance, rad
  Eigen::Vector2d previous_q = scenario.tip_angle_rad;
  std::size_t sample = 0;
  int segment = 0;

  auto emit = [&](double depth, const Eigen::Vector2d& load, bool tip_fixed) {
    models::JointState<double> state;
    state.encoder_angle_rad = scenario.tip_angle_rad;
    state.insertion_depth_m = depth;
    state.external_torque_nm = load;
    for (int j = 0; j < 2; ++j) {
      const double delta = truth.joints[j].backlash_rad;
      if (std::abs(load[j]) > scenario.sticking_torque_nm) {
        shaft_offset[j] = std::copysign(delta, load[j]);
      }
    }
    const Eigen::Vector2d q = scenario.tip_angle_rad + shaft_offset +
                              compliance(compliance_values.data(), state);
    state.encoder_angle_rad = q;
    const Eigen::Vector2d tau = bias(bias_values.data(), state) + load;
    const Eigen::Vector2d v = (q - previous_q) / dt;
    previous_q = q;
    const double t = double(sample) / scenario.sample_rate_hz;
    log.values.insert(log.values.end(),
                      {t, Quantise(q[0], scenario.encoder_count_rad),
                       Quantise(q[1], scenario.encoder_count_rad), depth,
                       tau[0] + effort_noise(rng), tau[1] + effort_noise(rng), v[0], v[1],
                       scenario.tip_angle_rad[0], scenario.tip_angle_rad[1],
                       tip_fixed ? 1.0 : 0.0, double(segment), 35.0 + 0.01 * t});
    ++sample;
  };

  const double first_depth =
      scenario.pushes.empty() ? 0.15 : scenario.pushes.front().insertion_depth_m;
  for (double s = 0.0; s < scenario.free_s; s += dt) emit(first_depth, {0.0, 0.0}, false);
  for (const Push& push : scenario.pushes) {
    ++segment;
    const Eigen::Vector2d axis(std::cos(push.direction_rad), std::sin(push.direction_rad));
    const double duration = 2.0 * push.ramp_s + push.hold_s;
    for (double s = 0.0; s <= duration + 0.5 * dt; s += dt) {
      emit(push.insertion_depth_m, push.peak_torque_nm * LoadFraction(push, s) * axis, true);
    }
  }
  return log;
}

}  // namespace pliant::experiments
