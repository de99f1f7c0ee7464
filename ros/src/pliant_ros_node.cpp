// pliant_ros: the compliance filter online, as a ROS 1 node (docs/ros.md).
//
//   subscribes  /ARM/measured_js          sensor_msgs/JointState (CRTK, the dVRK arm's own)
//   publishes   /ARM/pliant/measured_js    sensor_msgs/JointState: the input, all joints, with
//                                          position[0..1] (joints 1-2) corrected, same stamp
//               /ARM/pliant/measured_js_sd sensor_msgs/JointState: σ of corrected joints 1-2
//                                          in position[0..1] (rad), same stamp and names
//               /ARM/pliant/latency_s      std_msgs/Float64: seconds from the message's
//                                          arrival in the callback to its corrected publication
//   parameters  ~arm (string, default PSM1), ~params_file (string, required: a pliant
//               parameters file), ~queue_size (int, default 100)
// Every 10 s (and at exit) it logs how many messages it filtered and the
// latency's median and maximum.
#include <ros/ros.h>
#include <sensor_msgs/JointState.h>
#include <std_msgs/Float64.h>

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <exception>
#include <memory>
#include <string>
#include <vector>

#include "pliant/io/input_error.h"
#include "pliant/io/parameters_json.h"
#include "pliant/ros/joint_state_filter.h"

namespace {

class PliantNode {
 public:
  PliantNode(ros::NodeHandle& node, const std::string& arm,
             const pliant::models::ModelParameters& parameters, int queue_size)
      : filter_(parameters),
        corrected_(node.advertise<sensor_msgs::JointState>("/" + arm + "/pliant/measured_js",
                                                           queue_size)),
        sd_(node.advertise<sensor_msgs::JointState>("/" + arm + "/pliant/measured_js_sd",
                                                    queue_size)),
        latency_(node.advertise<std_msgs::Float64>("/" + arm + "/pliant/latency_s", queue_size)),
        measured_(node.subscribe("/" + arm + "/measured_js", queue_size, &PliantNode::OnMeasured,
                                 this, ros::TransportHints().tcpNoDelay())),
        report_(node.createWallTimer(ros::WallDuration(10.0), [this](const ros::WallTimerEvent&) {
          Report();
        })) {}

  // Median and maximum latency since the last report. After ros::spin()
  // returns, rosconsole is shut down: the last report goes to stdout itself.
  void Report(bool after_shutdown = false) {
    if (latencies_s_.empty()) return;
    std::sort(latencies_s_.begin(), latencies_s_.end());
    char text[200];
    std::snprintf(text, sizeof text,
                  "pliant_ros: %zu messages filtered; latency over the last %zu: median %.1f us, "
                  "max %.1f us",
                  filter_.messages(), latencies_s_.size(),
                  1e6 * latencies_s_[latencies_s_.size() / 2], 1e6 * latencies_s_.back());
    if (after_shutdown) {
      std::printf("%s\n", text);
    } else {
      ROS_INFO("%s", text);
    }
    latencies_s_.clear();
  }

 private:
  void OnMeasured(const sensor_msgs::JointState::ConstPtr& message) {
    const auto arrived = std::chrono::steady_clock::now();
    pliant::ros::JointStateIn in;
    in.stamp_ns = static_cast<std::int64_t>(message->header.stamp.toNSec());
    in.position = message->position;
    in.effort = message->effort;
    in.velocity = message->velocity;
    pliant::ros::JointStateOut out;
    std::string why;
    if (!filter_.Step(in, &out, &why)) {
      ROS_WARN_THROTTLE(5.0, "pliant_ros: skipped %s", why.c_str());
      return;
    }
    sensor_msgs::JointState corrected = *message;
    corrected.position = out.position;
    corrected_.publish(corrected);
    sensor_msgs::JointState sd;
    sd.header = message->header;
    sd.name.assign(message->name.begin(), message->name.begin() + std::min<std::size_t>(
                                                                      2, message->name.size()));
    sd.position = {out.sd_rad[0], out.sd_rad[1]};
    sd_.publish(sd);
    std_msgs::Float64 latency;
    latency.data =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - arrived).count();
    latency_.publish(latency);
    latencies_s_.push_back(latency.data);
  }

  pliant::ros::JointStateFilter filter_;
  ros::Publisher corrected_, sd_, latency_;
  ros::Subscriber measured_;
  ros::WallTimer report_;
  std::vector<double> latencies_s_;
};

}  // namespace

int main(int argc, char** argv) {
  ros::init(argc, argv, "pliant_ros");
  ros::NodeHandle node, private_node("~");
  std::string arm, params_file;
  private_node.param<std::string>("arm", arm, "PSM1");
  int queue_size = 100;
  private_node.param("queue_size", queue_size, 100);
  if (!private_node.getParam("params_file", params_file)) {
    ROS_FATAL("pliant_ros: set ~params_file to a pliant parameters file (docs/parameters.md), "
              "e.g. rosrun ... _params_file:=/path/to/params.json");
    return 2;
  }
  try {
    const auto parameters = pliant::io::ReadParameters(params_file);
    PliantNode pliant_node(node, arm, parameters, queue_size);
    ROS_INFO("pliant_ros: filtering /%s/measured_js with %s -> /%s/pliant/measured_js",
             arm.c_str(), params_file.c_str(), arm.c_str());
    ros::spin();
    pliant_node.Report(true);  // the messages since the last timed report
    std::fflush(stdout);
  } catch (const pliant::io::InputError& e) {
    ROS_FATAL("%s", e.what());
    return 2;
  } catch (const std::exception& e) {
    ROS_FATAL("pliant_ros: %s", e.what());
    return 1;
  }
  return 0;
}
