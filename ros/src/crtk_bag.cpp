// ROS 1 bag -> canonical log, through rosbag::Bag / rosbag::View and
// sensor_msgs::JointState (Debian's librosbag-dev, libsensor-msgs-dev).
#include "pliant/ros/crtk_bag.h"

#include <rosbag/bag.h>
#include <rosbag/exceptions.h>
#include <rosbag/view.h>
#include <sensor_msgs/JointState.h>

#include <algorithm>
#include <array>
#include <cstdint>
#include <fstream>
#include <limits>
#include <string>
#include <vector>

#include "pliant/io/input_error.h"

namespace pliant::ros {
namespace {

constexpr double kMissing = std::numeric_limits<double>::quiet_NaN();
const std::string kMeasuredSuffix = "/measured_js";
const std::string kJointStateType = "sensor_msgs/JointState";

struct JointSample {
  std::int64_t stamp_ns = 0;  ///< header.stamp
  std::array<double, 3> position{kMissing, kMissing, kMissing};
  std::array<double, 3> velocity{kMissing, kMissing, kMissing};
  std::array<double, 3> effort{kMissing, kMissing, kMissing};
};

struct Topic {
  std::string name;
  std::vector<JointSample> samples;
  std::vector<std::string> joint_names;  ///< of the first message
};

std::string FileName(const std::string& path) {
  const auto slash = path.find_last_of('/');
  return slash == std::string::npos ? path : path.substr(slash + 1);
}

std::string Join(const std::vector<std::string>& items) {
  std::string text;
  for (const auto& item : items) text += (text.empty() ? "" : ", ") + item;
  return text.empty() ? "(none)" : text;
}

void OpenBag(rosbag::Bag& bag, const std::string& path) {
  if (!std::ifstream(path)) {
    throw io::InputError(path, 0, 0, "cannot open the bag",
                         "check the path and that the file is readable");
  }
  try {
    bag.open(path, rosbag::bagmode::Read);
  } catch (const rosbag::BagException& e) {
    throw io::InputError(
        path, 0, 0, std::string("not a readable ROS 1 bag (rosbag: ") + e.what() + ")",
        "check that the file is a complete ROS 1 bag (rosbag info FILE); a bag cut "
        "short while recording can be repaired with rosbag reindex FILE");
  }
}

/// The arms whose /ARM/measured_js is a JointState topic, and every topic seen.
std::vector<std::string> ArmsInBag(const rosbag::Bag& bag, std::vector<std::string>* topics) {
  rosbag::View view(bag);
  std::vector<std::string> arms;
  for (const rosbag::ConnectionInfo* connection : view.getConnections()) {
    const std::string& topic = connection->topic;
    topics->push_back(topic);
    const bool measured = topic.size() > kMeasuredSuffix.size() + 1 && topic.front() == '/' &&
                          topic.compare(topic.size() - kMeasuredSuffix.size(),
                                        kMeasuredSuffix.size(), kMeasuredSuffix) == 0;
    if (!measured || connection->datatype != kJointStateType) continue;
    const std::string arm = topic.substr(1, topic.size() - 1 - kMeasuredSuffix.size());
    if (std::find(arms.begin(), arms.end(), arm) == arms.end()) arms.push_back(arm);
  }
  std::sort(arms.begin(), arms.end());
  std::sort(topics->begin(), topics->end());
  topics->erase(std::unique(topics->begin(), topics->end()), topics->end());
  return arms;
}

std::string ChooseArm(const rosbag::Bag& bag, const std::string& path, const std::string& wanted) {
  std::vector<std::string> topics;
  const std::vector<std::string> arms = ArmsInBag(bag, &topics);
  if (arms.empty()) {
    throw io::InputError(path, 0, 0,
                         "the bag has no " + kJointStateType +
                             " topic /ARM/measured_js; topics found: " + Join(topics),
                         "record the arm's CRTK joint state (rosbag record /PSM1/measured_js "
                         "/PSM1/setpoint_js), dVRK 2.x publishes it for every arm");
  }
  if (wanted.empty()) {
    if (arms.size() == 1) return arms.front();
    throw io::InputError(path, 0, 0, "the bag has measured_js for several arms: " + Join(arms),
                         "choose one with --arm NAME");
  }
  if (std::find(arms.begin(), arms.end(), wanted) == arms.end()) {
    throw io::InputError(
        path, 0, 0, "the bag has no /" + wanted + kMeasuredSuffix + "; arms found: " + Join(arms),
        "pass one of them with --arm NAME (names are case-sensitive)");
  }
  return wanted;
}

/// Copies the first three entries of a JointState array; false when there are fewer.
bool CopyFirstThree(const std::vector<double>& from, std::array<double, 3>& to,
                    std::size_t needed) {
  for (std::size_t i = 0; i < 3 && i < from.size(); ++i) to[i] = from[i];
  return from.size() >= needed;
}

JointSample ToSample(const sensor_msgs::JointState& message, const std::string& path,
                     const std::string& topic, std::size_t index, bool needs_effort) {
  JointSample sample;
  sample.stamp_ns = static_cast<std::int64_t>(message.header.stamp.toNSec());
  const auto too_short = [&](const char* field, std::size_t size, std::size_t needed) {
    return io::InputError(path, 0, 0,
                          "message " + std::to_string(index) + " on " + topic + " has " +
                              std::to_string(size) + " " + field + " entries, fewer than " +
                              std::to_string(needed),
                          "joints 1-3 need position[0..2] and effort[0..1]: record the arm's own "
                          "measured_js, not a reduced joint state");
  };
  if (!CopyFirstThree(message.position, sample.position, 3)) {
    throw too_short("position", message.position.size(), 3);
  }
  CopyFirstThree(message.velocity, sample.velocity, 0);
  if (!CopyFirstThree(message.effort, sample.effort, needs_effort ? 2 : 0)) {
    throw too_short("effort", message.effort.size(), 2);
  }
  return sample;
}

Topic ReadTopic(const rosbag::Bag& bag, const std::string& path, const std::string& name,
                bool needs_effort) {
  Topic topic{name, {}, {}};
  std::size_t index = 0;
  try {
    rosbag::View view(bag, rosbag::TopicQuery(name));
    for (const rosbag::MessageInstance& instance : view) {
      ++index;
      const auto message = instance.instantiate<sensor_msgs::JointState>();
      if (!message) {
        throw io::InputError(path, 0, 0,
                             name + " holds " + instance.getDataType() + ", not " + kJointStateType,
                             "the CRTK joint state topics are sensor_msgs/JointState");
      }
      if (topic.samples.empty()) topic.joint_names = message->name;
      topic.samples.push_back(ToSample(*message, path, name, index, needs_effort));
    }
  } catch (const io::InputError&) {
    throw;
  } catch (const std::exception& e) {  // rosbag and roscpp_serialization errors on a damaged bag
    throw io::InputError(path, 0, 0,
                         "message " + std::to_string(index + 1) + " on " + name +
                             " cannot be read (rosbag: " + e.what() + ")",
                         "the bag is damaged or cut short: check it with rosbag check FILE, or "
                         "record it again");
  }
  // The view orders by receive time; the log's time is the message's own stamp.
  std::stable_sort(
      topic.samples.begin(), topic.samples.end(),
      [](const JointSample& a, const JointSample& b) { return a.stamp_ns < b.stamp_ns; });
  return topic;
}

void CheckStampsIncrease(const Topic& measured, const std::string& path) {
  for (std::size_t i = 1; i < measured.samples.size(); ++i) {
    if (measured.samples[i].stamp_ns > measured.samples[i - 1].stamp_ns) continue;
    throw io::InputError(path, 0, 0,
                         measured.name + " has two messages with header.stamp " +
                             std::to_string(measured.samples[i].stamp_ns) + " ns (messages " +
                             std::to_string(i) + " and " + std::to_string(i + 1) +
                             " in stamp order)",
                         "the log's t must increase strictly: the publisher must stamp every joint "
                         "state with its own sampling time");
  }
}

/// The latest setpoint at or before stamp_ns, or nullptr before the first one.
const JointSample* LatestAtOrBefore(const std::vector<JointSample>& setpoints,
                                    std::int64_t stamp_ns) {
  const auto after =
      std::upper_bound(setpoints.begin(), setpoints.end(), stamp_ns,
                       [](std::int64_t t, const JointSample& s) { return t < s.stamp_ns; });
  return after == setpoints.begin() ? nullptr : &*(after - 1);
}

std::string StampText(std::int64_t stamp_ns) {
  std::string fraction = std::to_string(stamp_ns % 1000000000);
  fraction.insert(0, 9 - fraction.size(), '0');
  return std::to_string(stamp_ns / 1000000000) + "." + fraction;
}

io::LogHeader MakeHeader(const std::string& path, const std::string& arm, const Topic& measured,
                         const Topic* setpoint) {
  io::LogHeader header;
  header.metadata = {
      {"source", FileName(path)},
      {"format", "ros1-bag"},
      {"arm", arm},
      {"start_time", StampText(measured.samples.front().stamp_ns) +
                         " s (UNIX time, header.stamp of the first " + measured.name +
                         "; t counts from it)"},
      {"joint_names", Join(measured.joint_names)},
  };
  header.columns = {"t", "q1", "q2", "q3", "tau1", "tau2", "tau3", "v1", "v2", "v3"};
  if (setpoint != nullptr) {
    header.metadata.emplace_back("setpoint", "q*_cmd = position of the latest " + setpoint->name +
                                                 " with header.stamp at or before the row's " +
                                                 measured.name + " header.stamp");
    for (const char* name : {"q1_cmd", "q2_cmd", "q3_cmd"}) header.columns.emplace_back(name);
  }
  return header;
}

io::Log MakeLog(const std::string& path, const std::string& arm, const Topic& measured,
                const Topic* setpoint) {
  io::Log log;
  log.header = MakeHeader(path, arm, measured, setpoint);
  const std::int64_t start_ns = measured.samples.front().stamp_ns;
  log.values.reserve(measured.samples.size() * log.header.columns.size());
  for (const JointSample& s : measured.samples) {
    log.values.push_back(static_cast<double>(s.stamp_ns - start_ns) / 1e9);
    for (int i = 0; i < 3; ++i) log.values.push_back(s.position[i]);
    for (int i = 0; i < 3; ++i) log.values.push_back(s.effort[i]);
    for (int i = 0; i < 3; ++i) log.values.push_back(s.velocity[i]);
    if (setpoint == nullptr) continue;
    const JointSample* command = LatestAtOrBefore(setpoint->samples, s.stamp_ns);
    for (int i = 0; i < 3; ++i) log.values.push_back(command ? command->position[i] : kMissing);
  }
  return log;
}

}  // namespace

io::Log ReadCrtkBag(const std::string& path, const CrtkBagOptions& options) {
  rosbag::Bag bag;
  OpenBag(bag, path);
  const std::string arm = ChooseArm(bag, path, options.arm);
  const Topic measured = ReadTopic(bag, path, "/" + arm + kMeasuredSuffix, true);
  if (measured.samples.empty()) {
    throw io::InputError(path, 0, 0, "/" + arm + kMeasuredSuffix + " has no messages",
                         "record the arm while it publishes its joint state");
  }
  CheckStampsIncrease(measured, path);
  const Topic setpoint = ReadTopic(bag, path, "/" + arm + "/setpoint_js", false);
  return MakeLog(path, arm, measured, setpoint.samples.empty() ? nullptr : &setpoint);
}

io::BagReader CrtkBagReader() {
  return [](const std::string& path, const std::string& arm) { return ReadCrtkBag(path, {arm}); };
}

}  // namespace pliant::ros
