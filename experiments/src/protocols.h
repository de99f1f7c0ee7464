#pragma once
// The paper's protocols as sequences of phases. A phase is a commanded
// trajectory of the three joints for a while, with the tip free or held, and
// optionally a hold (its last samples, averaged) at the end. Protocols that
// react to what they measure (the clamped beam reverses when the effort passes
// a limit) receive the means of the last hold before choosing the next phase.

#include <Eigen/Core>
#include <deque>
#include <functional>
#include <memory>
#include <vector>

#include "pliant/experiments/scenario.h"
#include "pliant/experiments/simulator.h"
#include "pliant/experiments/truth_model.h"

namespace pliant::experiments::detail {

struct Phase {
  double duration_s = 0.0;
  /// q1, q2 (rad) and q3 (m) commanded at time s since the phase began.
  std::function<Eigen::Vector3d(double)> command;
  int hold_samples = 0;  ///< the phase's last samples form a hold
  bool tip_fixed = false;
  int segment = 0;
};

class Protocol {
 public:
  virtual ~Protocol() = default;
  /// The next phase, given the last hold (nullptr before the first); false when done.
  virtual bool Next(const HoldRecord* last_hold, Phase* phase) = 0;
  const std::vector<SegmentInfo>& segments() const { return segments_; }

 protected:
  int AddSegment(int joint, double depth_m, int direction, std::string label) {
    const int id = static_cast<int>(segments_.size()) + 1;
    segments_.push_back({id, joint, depth_m, direction, std::move(label)});
    return id;
  }
  std::vector<SegmentInfo> segments_;
};

/// A protocol whose phases do not depend on measurements.
class FixedProtocol : public Protocol {
 public:
  bool Next(const HoldRecord*, Phase* phase) override {
    if (phases_.empty()) return false;
    *phase = std::move(phases_.front());
    phases_.pop_front();
    return true;
  }

 protected:
  std::deque<Phase> phases_;
};

/// Minimum-jerk motion from `from` to `to` over move_s, then held.
std::function<Eigen::Vector3d(double)> MinimumJerk(const Eigen::Vector3d& from,
                                                   const Eigen::Vector3d& to, double move_s);

/// Seconds to move between two poses at a gentle transit speed (tip free).
double TransitTime(const Eigen::Vector3d& from, const Eigen::Vector3d& to);

std::unique_ptr<Protocol> MakeProtocol(const Scenario& scenario, double period_s);

// One per experiment (protocols.cpp, protocols_contact.cpp).
std::unique_ptr<Protocol> MakeBiasSweep(const Scenario& scenario, double period_s);
std::unique_ptr<Protocol> MakeFreeMotion(const Scenario& scenario, double period_s);
std::unique_ptr<Protocol> MakeClampedBeam(const Scenario& scenario, double period_s);
std::unique_ptr<Protocol> MakeDivot(const Scenario& scenario, double period_s);

}  // namespace pliant::experiments::detail
