// Protocols with the tip held: the clamped beam (paper §3, Figs. 3 and 5) and
// pushes into a divot (paper §3, Figs. 7-8).
#include <cmath>
#include <cstdio>

#include "protocols.h"

namespace pliant::experiments::detail {
namespace {

constexpr double kPi = 3.14159265358979323846;

class ClampedBeam : public Protocol {
 public:
  ClampedBeam(const Scenario& scenario, double period_s)
      : p_(scenario.clamped_beam), hold_s_(p_.hold_samples * period_s) {
    for (double depth : p_.depths_m) {
      for (int joint : p_.joints) runs_.push_back({depth, joint});
    }
    command_ << p_.clamp_angle_rad, p_.depths_m.front();
  }

  bool Next(const HoldRecord* last, Phase* phase) override {
    if (stage_ == Stage::kTransit) {
      if (run_ == runs_.size()) return false;
      const Eigen::Vector3d pose(p_.clamp_angle_rad[0], p_.clamp_angle_rad[1], runs_[run_].depth_m);
      const double transit = TransitTime(command_, pose);
      *phase = {transit + p_.settle_s, MinimumJerk(command_, pose, transit), 0, false, 0};
      command_ = start_ = pose;
      stage_ = Stage::kClamp;
      return true;
    }
    const int j = runs_[run_].joint - 1;
    if (stage_ == Stage::kClamp) {
      // The tip is clamped where it rests; the first hold is the unloaded reference.
      leg_ = 0;
      direction_ = +1;
      steps_ = 0;
      segment_ = NewSegment();
      *phase = {p_.settle_s + hold_s_, MinimumJerk(command_, command_, 0.0), p_.hold_samples, true,
                segment_};
      stage_ = Stage::kStepping;
      return true;
    }
    const double step_rad = p_.tip_step_m / runs_[run_].depth_m;
    // The load this leg builds, in its own direction: just after a reversal the
    // effort still exceeds the limit the other way, and |effort| would end the
    // new leg after one step (the sweep then never came back past the start).
    const bool past_limit = direction_ * last->effort_nm[j] > p_.effort_limit_nm;
    if (leg_ < 2 && (past_limit || steps_ >= p_.max_steps_per_leg)) {
      ++leg_;
      direction_ = -direction_;
      steps_ = 0;
      segment_ = NewSegment();
    } else if (leg_ == 2 && ((command_[j] - start_[j]) * direction_ > 0.5 * step_rad ||
                             steps_ >= p_.max_steps_per_leg)) {
      ++run_;  // back past the start: this run is done, release the clamp
      stage_ = Stage::kTransit;
      return Next(nullptr, phase);
    }
    Eigen::Vector3d target = command_;
    target[j] += direction_ * step_rad;
    *phase = {p_.move_s + p_.settle_s + hold_s_, MinimumJerk(command_, target, p_.move_s),
              p_.hold_samples, true, segment_};
    command_ = target;
    ++steps_;
    return true;
  }

 private:
  enum class Stage { kTransit, kClamp, kStepping };
  struct Run {
    double depth_m;
    int joint;
  };

  int NewSegment() {
    char label[96];
    std::snprintf(label, sizeof label, "clamped_beam joint %d depth %.3f m leg %d (%c)",
                  runs_[run_].joint, runs_[run_].depth_m, leg_ + 1, direction_ > 0 ? '+' : '-');
    return AddSegment(runs_[run_].joint, runs_[run_].depth_m, direction_, label);
  }

  ClampedBeamProtocol p_;
  double hold_s_;
  std::vector<Run> runs_;
  std::size_t run_ = 0;
  Stage stage_ = Stage::kTransit;
  Eigen::Vector3d command_, start_;
  int leg_ = 0, direction_ = +1, steps_ = 0, segment_ = 0;
};

class Divot : public FixedProtocol {
 public:
  explicit Divot(const Scenario& scenario) {
    const DivotProtocol& p = scenario.divot;
    const Truth& truth = scenario.truth;
    Eigen::Vector3d last(p.divot_angle_rad[0], p.divot_angle_rad[1], p.depths_m.front());
    for (double depth : p.depths_m) {
      const Eigen::Vector3d seat(p.divot_angle_rad[0], p.divot_angle_rad[1], depth);
      const double transit = TransitTime(last, seat);
      phases_.push_back({transit + p.rest_s, MinimumJerk(last, seat, transit), 0, false, 0});
      last = seat;
      for (double direction_deg : p.directions_deg) {
        for (double peak : p.peak_torques_nm) {
          for (double speed : p.speeds_rad_s) {
            // Command the joints to where the truth says the nominal load
            // builds: across the clearance, then bending by K(L)·tau.
            const double a = direction_deg * kPi / 180.0;
            const Eigen::Vector2d load(peak * std::cos(a), peak * std::sin(a));
            Eigen::Vector3d target = seat;
            for (int j = 0; j < 2; ++j) {
              if (std::abs(load[j]) < 1e-6) continue;
              target[j] += truth.backlash_centre_rad[j] +
                           std::copysign(truth.joints[j].backlash_rad, load[j]) +
                           models::ComplianceAt(truth.joints[j], depth) * load[j];
            }
            const double ramp =
                std::max(0.05, (target - seat).head<2>().cwiseAbs().maxCoeff() / speed);
            char label[128];
            std::snprintf(label, sizeof label,
                          "divot depth %.3f m direction %.0f deg peak %.2f N·m speed %.3f rad/s",
                          depth, direction_deg, peak, speed);
            const int joint = std::abs(load[1]) < 1e-6 ? 1 : (std::abs(load[0]) < 1e-6 ? 2 : 0);
            const int segment = AddSegment(joint, depth, 0, label);
            const auto up = MinimumJerk(seat, target, ramp);
            const auto down = MinimumJerk(target, seat, ramp);
            const double back = ramp + p.hold_s;
            auto command = [up, down, back](double s) { return s < back ? up(s) : down(s - back); };
            phases_.push_back({2.0 * ramp + p.hold_s + p.rest_s, command, 0, true, segment});
          }
        }
      }
    }
  }
};

}  // namespace

std::unique_ptr<Protocol> MakeClampedBeam(const Scenario& scenario, double period_s) {
  return std::make_unique<ClampedBeam>(scenario, period_s);
}

std::unique_ptr<Protocol> MakeDivot(const Scenario& scenario, double) {
  return std::make_unique<Divot>(scenario);
}

}  // namespace pliant::experiments::detail
