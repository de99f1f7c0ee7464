#pragma once
// The signed encoder travel of each joint since it last reversed: the state
// the held-friction effect (effects/held_friction.h) reads. Every consumer
// that walks a log row by row (pliant correct, the filter, identification)
// keeps one TravelSinceReversal and feeds it each row's encoder angles.
//
// A reversal counts only once the joint has come back more than
// `reversal_threshold_rad` from its furthest point, so that encoder noise at
// rest (or a count's jitter) does not flip the direction.

#include <algorithm>
#include <cmath>

#include <Eigen/Core>

namespace pliant::models {

class TravelSinceReversal {
 public:
  explicit TravelSinceReversal(double reversal_threshold_rad = 2e-4)
      : threshold_rad_(reversal_threshold_rad) {}

  /// Feeds one row's encoder angles (rad; NaN = not recorded, skipped) and
  /// returns the signed travel since the last reversal (rad): positive while
  /// the joint moves toward +q, 0 until it has moved at all.
  Eigen::Vector2d Update(const Eigen::Vector2d& angle_rad) {
    Eigen::Vector2d travel;
    for (int j = 0; j < 2; ++j) travel[j] = UpdateJoint(&joints_[j], angle_rad[j]);
    return travel;
  }

  /// Forgets the history (a new log, or a pose that jumped).
  void Reset() { joints_[0] = joints_[1] = Joint{}; }

 private:
  struct Joint {
    bool started = false;
    double direction = 0.0;  // +1, −1, or 0 before the first motion
    double origin_rad = 0.0;   // where the current motion began
    double extreme_rad = 0.0;  // furthest point in the current direction
  };

  double UpdateJoint(Joint* s, double q) const {
    if (!std::isfinite(q)) return 0.0;
    if (!s->started) {
      *s = Joint{true, 0.0, q, q};
      return 0.0;
    }
    if (s->direction == 0.0) {
      if (std::abs(q - s->origin_rad) <= threshold_rad_) return 0.0;
      s->direction = q > s->origin_rad ? 1.0 : -1.0;
      s->extreme_rad = q;
    } else if (s->direction * (s->extreme_rad - q) > threshold_rad_) {
      s->direction = -s->direction;  // came back past the threshold: a reversal
      s->origin_rad = s->extreme_rad;
      s->extreme_rad = q;
    } else if (s->direction * (q - s->extreme_rad) > 0.0) {
      s->extreme_rad = q;
    }
    return s->direction * std::max(0.0, s->direction * (q - s->origin_rad));
  }

  double threshold_rad_;
  Joint joints_[2];
};

}  // namespace pliant::models
