#pragma once
// ROS 1 bags of a dVRK arm's CRTK topics -> the canonical log
// (docs/log-format.md, docs/import.md), read with Debian's rosbag library.
//
//   /ARM/measured_js (sensor_msgs/JointState):
//     t = header.stamp − header.stamp of the first message (s)
//     q1 q2 q3 = position[0..2] (rad, rad, m), v1 v2 v3 = velocity[0..2],
//     tau1 tau2 tau3 = effort[0..2] (N·m, N·m, N)
//   /ARM/setpoint_js, when the bag has it:
//     q1_cmd q2_cmd q3_cmd = position[0..2] of the latest setpoint whose
//     header.stamp is at or before the row's measured_js header.stamp
//     (empty before the first setpoint).
// Metadata says the source, the arm, the absolute start time and the sampling.
// Available only when pliant was built with ROS 1 (PLIANT_HAVE_ROS1 is defined).

#include <string>

#include "pliant/io/import.h"
#include "pliant/io/log.h"

namespace pliant::ros {

struct CrtkBagOptions {
  std::string arm;  ///< e.g. "PSM2"; "" = the only arm that publishes measured_js
};

/// Reads one arm's joint states from a bag.
/// @throws io::InputError for a file that is not a readable bag, a bag without
///   measured_js, an arm name the bag does not have (the message lists the arms
///   found), several arms and no name, or messages too short for joints 1–3.
pliant::io::Log ReadCrtkBag(const std::string& path, const CrtkBagOptions& options);

/// ReadCrtkBag as io::ImportRecording takes a bag reader (path, arm): what
/// `pliant import` and pliant.import_recording hand it where ROS 1 was built.
pliant::io::BagReader CrtkBagReader();

}  // namespace pliant::ros
