// Protocols without contact: the bias sweep (paper §3, Fig. 4) and free motion.
#include "protocols.h"

#include <cmath>
#include <cstdio>
#include <stdexcept>

namespace pliant::experiments::detail {
namespace {

constexpr double kPi = 3.14159265358979323846;
constexpr double kDegree = kPi / 180.0;

// 3x² − 2x³: a fade-in with zero slope at both ends.
double SmoothStep(double x) {
  if (x <= 0.0) return 0.0;
  if (x >= 1.0) return 1.0;
  return x * x * (3.0 - 2.0 * x);
}

std::string Label(const char* experiment, int joint, double depth_m) {
  char text[96];
  std::snprintf(text, sizeof text, "%s joint %d depth %.3f m", experiment, joint, depth_m);
  return text;
}

class BiasSweep : public FixedProtocol {
 public:
  BiasSweep(const Scenario& scenario, double period_s) {
    const BiasSweepProtocol& p = scenario.bias_sweep;
    Eigen::Vector3d last(0.0, 0.0, p.depths_m.front());
    for (double depth : p.depths_m) {
      for (int j = 0; j < 2; ++j) {
        const auto& range = j == 0 ? p.joint1_range_deg : p.joint2_range_deg;
        Eigen::Vector3d pose(0.0, 0.0, depth);
        pose[j] = range[0] * kDegree;
        const double transit = TransitTime(last, pose);
        phases_.push_back({transit + p.settle_s, MinimumJerk(last, pose, transit), 0, false, 0});
        last = pose;
        const int segment = AddSegment(j + 1, depth, +1, Label("bias_sweep", j + 1, depth));
        const double hold_s = p.hold_samples * period_s;
        for (double angle = range[0]; angle <= range[1] + 1e-9; angle += p.step_deg) {
          Eigen::Vector3d target = last;
          target[j] = angle * kDegree;
          const double move = angle == range[0] ? 0.0 : p.move_s;
          phases_.push_back({move + p.settle_s + hold_s, MinimumJerk(last, target, move),
                             p.hold_samples, false, segment});
          last = target;
        }
      }
    }
  }
};

class FreeMotion : public FixedProtocol {
 public:
  explicit FreeMotion(const Scenario& scenario) {
    const FreeMotionProtocol p = scenario.free_motion;
    const int segment = AddSegment(0, p.depth_mid_m, 0, "free_motion");
    auto command = [p](double s) {
      const double fade = p.ramp_s > 0.0 ? SmoothStep(s / p.ramp_s) : 1.0;
      return Eigen::Vector3d(
          fade * p.amplitude_rad[0] * std::sin(2.0 * kPi * p.frequency_hz[0] * s),
          fade * p.amplitude_rad[1] * std::sin(2.0 * kPi * p.frequency_hz[1] * s),
          p.depth_mid_m +
              fade * p.depth_amplitude_m * std::sin(2.0 * kPi * p.depth_frequency_hz * s));
    };
    phases_.push_back({p.duration_s, command, 0, false, segment});
  }
};

}  // namespace

std::function<Eigen::Vector3d(double)> MinimumJerk(const Eigen::Vector3d& from,
                                                   const Eigen::Vector3d& to, double move_s) {
  return [from, to, move_s](double s) -> Eigen::Vector3d {
    if (move_s <= 0.0 || s >= move_s) return to;
    const double x = s / move_s;
    const double shape = x * x * x * (10.0 - x * (15.0 - 6.0 * x));
    return from + shape * (to - from);
  };
}

double TransitTime(const Eigen::Vector3d& from, const Eigen::Vector3d& to) {
  // Peak speeds 0.5 rad/s and 0.05 m/s; a minimum-jerk move peaks at 1.875×
  // its mean speed.
  const Eigen::Vector3d delta = (to - from).cwiseAbs();
  const double slowest = std::max({delta[0] / 0.5, delta[1] / 0.5, delta[2] / 0.05});
  return std::max(0.5, 1.875 * slowest);
}

std::unique_ptr<Protocol> MakeBiasSweep(const Scenario& scenario, double period_s) {
  return std::make_unique<BiasSweep>(scenario, period_s);
}

std::unique_ptr<Protocol> MakeFreeMotion(const Scenario& scenario, double) {
  return std::make_unique<FreeMotion>(scenario);
}

std::unique_ptr<Protocol> MakeProtocol(const Scenario& scenario, double period_s) {
  switch (scenario.type) {
    case ExperimentType::kBiasSweep:
      return MakeBiasSweep(scenario, period_s);
    case ExperimentType::kClampedBeam:
      return MakeClampedBeam(scenario, period_s);
    case ExperimentType::kDivot:
      return MakeDivot(scenario, period_s);
    case ExperimentType::kFreeMotion:
      return MakeFreeMotion(scenario, period_s);
  }
  throw std::logic_error("unknown experiment type");
}

}  // namespace pliant::experiments::detail
