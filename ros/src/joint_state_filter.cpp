#include "pliant/ros/joint_state_filter.h"

#include <cmath>

namespace pliant::ros {

JointStateFilter::JointStateFilter(const models::ModelParameters& parameters,
                                   const estimation::FilterOptions& options)
    : filter_(parameters, options) {}

bool JointStateFilter::Step(const JointStateIn& in, JointStateOut* out, std::string* why) {
  if (in.position.size() < 3 || in.effort.size() < 2) {
    *why = "a measured_js with " + std::to_string(in.position.size()) + " positions and " +
           std::to_string(in.effort.size()) + " efforts (joints 1-3 need 3 and 2)";
    return false;
  }
  if (messages_ > 0 && in.stamp_ns <= last_stamp_ns_) {
    *why = "a measured_js stamped " + std::to_string(in.stamp_ns) + " ns, not after the previous " +
           std::to_string(last_stamp_ns_) + " ns";
    return false;
  }
  if (messages_ == 0) first_stamp_ns_ = in.stamp_ns;
  last_stamp_ns_ = in.stamp_ns;
  ++messages_;
  estimation::FilterSample sample;
  // The same expression as the bag reader's t, so that both give the same double.
  sample.time_s = static_cast<double>(in.stamp_ns - first_stamp_ns_) / 1e9;
  sample.encoder_rad << in.position[0], in.position[1];
  sample.insertion_depth_m = in.position[2];
  sample.effort_nm << in.effort[0], in.effort[1];
  if (in.velocity.size() >= 2) sample.velocity_rad_s << in.velocity[0], in.velocity[1];
  const estimation::FilterEstimate estimate = filter_.Step(sample);
  out->position = in.position;
  out->position[0] = estimate.corrected_rad[0];
  out->position[1] = estimate.corrected_rad[1];
  out->sd_rad[0] = std::sqrt(estimate.covariance_rad2(0, 0));
  out->sd_rad[1] = std::sqrt(estimate.covariance_rad2(1, 1));
  out->flags = estimate.flags;
  return true;
}

}  // namespace pliant::ros
