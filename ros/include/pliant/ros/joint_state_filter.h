#pragma once
// The filter on a stream of CRTK joint states (sensor_msgs/JointState of a
// dVRK PSM: position, velocity, effort of outer_yaw, outer_pitch,
// outer_insertion, ...), as the pliant_ros node runs it, free of ROS so that
// it is tested without a ROS master.
//
// Each message becomes one filter sample exactly as `pliant import` then
// `pliant filter` would make it from the same bag (ros/include/pliant/ros/crtk_bag.h):
//   t = (header.stamp − header.stamp of the first message) in s,
//   q1 q2 q3 = position[0..2] (rad, rad, m), tau1 tau2 = effort[0..1] (N·m),
// no reference and no held tip (a live arm's tip is not known to be held).
// The output is the message with position[0..1] replaced by the corrected
// joints, and their standard deviations.

#include <cstdint>
#include <string>
#include <vector>

#include "pliant/estimation/filter.h"
#include "pliant/models/parameters.h"

namespace pliant::ros {

/// One joint-state message's fields the filter reads.
struct JointStateIn {
  std::int64_t stamp_ns = 0;  ///< header.stamp, ns
  std::vector<double> position, effort;
  /// The message's velocity (rad/s) where it has joints 1–2's, as the bag
  /// reader's v1, v2: the file's effects and the motor tracker's start read it.
  std::vector<double> velocity;
};

/// What is published for one message.
struct JointStateOut {
  std::vector<double> position;  ///< the input's, joints 1–2 corrected (rad)
  double sd_rad[2] = {0.0, 0.0};  ///< σ of corrected q1, q2 (rad)
  std::uint32_t flags = 0;       ///< estimation::FilterFlag bits
};

class JointStateFilter {
 public:
  JointStateFilter(const models::ModelParameters& parameters,
                   const estimation::FilterOptions& options = {});

  /// Filters one message. Returns false (and leaves `out` alone) for a message
  /// the filter cannot take: fewer than three positions or two efforts, or a
  /// stamp not after the previous one's (a log's t must increase); `why` says
  /// which.
  bool Step(const JointStateIn& in, JointStateOut* out, std::string* why);

  std::size_t messages() const { return messages_; }

 private:
  estimation::ComplianceFilter filter_;
  std::int64_t first_stamp_ns_ = 0;
  std::int64_t last_stamp_ns_ = 0;
  std::size_t messages_ = 0;
};

}  // namespace pliant::ros
