#pragma once
// What identification sees of a set of logs: quasi-static samples of joints 1
// and 2, each tagged with the tip segment it belongs to. The paper averaged 20
// measurements at each position (section 3); pliant does the same with the
// rows of a hold, and drops rows taken while a joint moves, where inertia and
// friction break the quasi-static model (tau_meas = tau0(q) + tau_ext).

#include <cstddef>
#include <string>
#include <vector>

#include <Eigen/Core>

#include "pliant/io/log.h"

namespace pliant::estimation {

struct IdentificationSample {
  Eigen::Vector2d angle_rad = Eigen::Vector2d::Zero();  ///< q1, q2 (encoders)
  double insertion_depth_m = 0.0;                       ///< q3
  Eigen::Vector2d effort_nm = Eigen::Vector2d::Zero();  ///< tau1, tau2 (measured)
  bool tip_fixed = false;  ///< the tip is held (clamp, divot): its angle is a latent constant
  int segment = 0;         ///< 0, 1, … over all logs: a run of rows with one tip state
  int rows = 1;            ///< log rows averaged into this sample
  int log = 0;             ///< which log (0, 1, …): each log is its own clamp
  /// Signed encoder travel since each joint last reversed (rad), over the
  /// log's rows so far (models::TravelSinceReversal): the held-friction state.
  Eigen::Vector2d travel_since_reversal_rad = Eigen::Vector2d::Zero();
};

struct SampleExtractionOptions {
  /// Average consecutive resting rows into one sample (the paper's hold means).
  bool average_holds = true;
  /// A hold ends when q1 or q2 leaves its first value by more than this (rad).
  double hold_tolerance_rad = 5e-5;
  /// Rows faster than this on joint 1 or 2 (|v|, rad/s; when the log has v1, v2)
  /// are moving: dropped.
  double rest_velocity_rad_s = 0.02;

  bool IsValid(std::string* error) const;
};

struct IdentificationData {
  std::vector<IdentificationSample> samples;
  std::size_t log_rows = 0;       ///< rows read over all logs
  std::size_t moving_rows = 0;    ///< rows dropped as moving
  int segments = 0;               ///< number of distinct segment ids
  std::vector<std::string> logs;  ///< names of the logs, in order

  std::size_t CountTipFixed() const;
};

/// Appends one log's samples. A segment is a maximal run of rows with the same
/// `segment` value (0 when the log has none) and the same `tip_fixed` (0 when
/// the log has none).
void AppendSamples(const io::Log& log, const std::string& name,
                   const SampleExtractionOptions& options, IdentificationData* data);

}  // namespace pliant::estimation
