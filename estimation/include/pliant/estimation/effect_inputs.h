#pragma once
// What a catalogue effect sees of each row of a log, tracked row by row for
// every consumer: the diagnosis and identify --effect fit the effects on
// these inputs, and pliant correct, the filter (and with it the smoother)
// stream a log through them, so that an effect a parameters file holds acts
// on every consumer as it was fitted.

#include <array>
#include <limits>
#include <vector>

#include <Eigen/Core>

#include "pliant/io/log.h"
#include "pliant/models/effect.h"
#include "pliant/models/parameters.h"
#include "pliant/models/travel_since_reversal.h"

namespace pliant::estimation {

class EffectInputs {
 public:
  /// quasi_static: the rows are poses (t a pose index): no velocity and no
  /// effort rate, as the diagnosis reads such a log; so is a row more than
  /// max_step_s after the last (a pose log without its mark, a time gap:
  /// FilterOptions::time_gap_s). effort_rate_window_s: the span of the
  /// effort's rate line through the last window_s of rows (causal: a stream
  /// has no later rows; the fit reads the same line centred on its row,
  /// diagnosis::CentredEffortRates).
  explicit EffectInputs(bool quasi_static = false, double max_step_s = 0.1,
                        double effort_rate_window_s = 0.1);

  /// This row's inputs: encoder angles and depth q (rad, rad, m), the time
  /// (s), the measured efforts (N·m) and the log's joint velocities (rad/s;
  /// NaN where it has none: the encoders' backward difference instead). The
  /// acceleration is the velocities' trailing line over the effort rate's
  /// window. The external torque is left 0 (the consumer sets it).
  const models::JointState<double>& Update(double time_s, const Eigen::Vector3d& q,
                                           const Eigen::Vector2d& effort_nm,
                                           const Eigen::Vector2d& velocity_rad_s);
  /// The same from one row of a log (its values in `columns`' order; a
  /// column the log lacks reads NaN): what every consumer that walks a log
  /// feeds it.
  const models::JointState<double>& Update(const io::StandardColumns& columns, const double* row);
  const models::JointState<double>& state() const { return state_; }

 private:
  void AddEffort(double time_s, const Eigen::Vector2d& effort_nm,
                 const Eigen::Vector2d& velocity_rad_s);
  void DropOldest();
  void Sum(int slot, double sign);
  void Resum();

  bool quasi_static_;
  double max_step_s_, window_s_;
  models::JointState<double> state_;
  models::TravelSinceReversal travel_;
  double last_time_ = std::numeric_limits<double>::quiet_NaN();
  Eigen::Vector2d last_angle_{0.0, 0.0};
  // The efforts and velocities (channels 0–1, 2–3) of the last window, a
  // ring; the rate lines' sums about the anchor time, re-added from the ring
  // every kRing rows (no drift).
  static constexpr int kRing = 512, kChannels = 4;
  std::array<double, kRing> time_{}, value_[kChannels]{};
  double last_effort_[2] = {0.0, 0.0};  // what a missing sample of one joint repeats
  int oldest_ = 0, count_ = 0, since_resum_ = 0;
  double anchor_s_ = 0.0, n_ = 0.0, st_ = 0.0, stt_ = 0.0, sy_[kChannels] = {},
         sty_[kChannels] = {};
};

/// The effort's rate (N·m/s) at each row of a whole log, for the consumers
/// that fit on it (the diagnosis, identify --effect): the slope of the
/// least-squares line through the rows within ±window_s/2 that no gap (a step
/// beyond max_step_s) separates from the row — EffectInputs' trailing line
/// read half a window later. 0 on a quasi-static log.
std::vector<Eigen::Vector2d> CentredEffortRates(const io::Log& log, double window_s = 0.1,
                                                double max_step_s = 0.1);
/// The joints' acceleration (rad/s²) at each row, centred the same way.
std::vector<Eigen::Vector2d> CentredAccelerations(const io::Log& log, double window_s = 0.1,
                                                  double max_step_s = 0.1);

/// The log with the internal torque of `parameters`' effects taken out of
/// its efforts, row by row at EffectInputs' inputs (the effort's rate
/// centred, as the effects were fitted): what a bias table fitted beside
/// those effects should read.
io::Log WithoutInternalTorque(const io::Log& log, const models::ModelParameters& parameters);

}  // namespace pliant::estimation
