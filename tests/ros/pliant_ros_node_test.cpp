// pliant_ros against a real ROS master: roscore on a free loopback port, the
// shared CRTK bag played into the node by `rosbag play`, and every corrected
// message checked against `pliant filter` on the same bag's log.
#include <arpa/inet.h>
#include <fcntl.h>
#include <netinet/in.h>
#include <signal.h>
#include <sys/socket.h>
#include <sys/wait.h>
#include <unistd.h>

#include <gtest/gtest.h>
#include <ros/ros.h>
#include <sensor_msgs/JointState.h>

#include <chrono>
#include <cstdlib>
#include <filesystem>
#include <functional>
#include <mutex>
#include <string>
#include <thread>
#include <vector>

#include "pliant/io/log_reader.h"
#include "pliant/io/log_writer.h"
#include "pliant/ros/crtk_bag.h"

namespace pliant::ros {
namespace {

namespace fs = std::filesystem;
using Clock = std::chrono::steady_clock;

const std::string kBag = PLIANT_SOURCE_DIR "/data/real/crtk-rosbag/pitch_exp_traj_01_test_cropped.bag";
const std::string kParams = PLIANT_SOURCE_DIR "/data/paper.json";

// A TCP port nobody listens on now, on the loopback interface.
int FreePort() {
  const int fd = ::socket(AF_INET, SOCK_STREAM, 0);
  sockaddr_in address{};
  address.sin_family = AF_INET;
  address.sin_addr.s_addr = htonl(INADDR_LOOPBACK);
  socklen_t length = sizeof address;
  ::bind(fd, reinterpret_cast<sockaddr*>(&address), sizeof address);
  ::getsockname(fd, reinterpret_cast<sockaddr*>(&address), &length);
  ::close(fd);
  return ntohs(address.sin_port);
}

// A child process in its own process group (roscore starts rosmaster and
// rosout: the group is stopped as one), its output to `log`.
pid_t Spawn(const std::vector<std::string>& args, const fs::path& log) {
  const pid_t child = ::fork();
  if (child != 0) return child;
  ::setpgid(0, 0);
  const int out = ::open(log.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
  ::dup2(out, STDOUT_FILENO);
  ::dup2(out, STDERR_FILENO);
  std::vector<char*> argv;
  for (const std::string& a : args) argv.push_back(const_cast<char*>(a.c_str()));
  argv.push_back(nullptr);
  ::execvp(argv[0], argv.data());
  ::_exit(127);
}

// SIGINT to the group, SIGKILL after `grace`; returns the exit status.
int Stop(pid_t child, std::chrono::seconds grace) {
  ::kill(-child, SIGINT);
  const auto deadline = Clock::now() + grace;
  int status = 0;
  while (::waitpid(child, &status, WNOHANG) == 0) {
    if (Clock::now() > deadline) {
      ::kill(-child, SIGKILL);
      ::waitpid(child, &status, 0);
      break;
    }
    std::this_thread::sleep_for(std::chrono::milliseconds(50));
  }
  return status;
}

bool WaitFor(const std::function<bool()>& ready, std::chrono::seconds limit) {
  const auto deadline = Clock::now() + limit;
  while (!ready()) {
    if (Clock::now() > deadline) return false;
    std::this_thread::sleep_for(std::chrono::milliseconds(100));
  }
  return true;
}

bool OnPath(const std::string& program) {
  return std::system(("command -v " + program + " >/dev/null 2>&1").c_str()) == 0;
}

struct Received {
  std::mutex mutex;
  std::vector<sensor_msgs::JointState> corrected, sd;
};

TEST(PliantRosNode, CorrectsEveryMessageOfTheRealBagAsPliantFilterDoes) {
  for (const char* program : {"roscore", "rosbag"}) {
    if (!OnPath(program)) GTEST_SKIP() << program << " not found (Debian: ros-core, python3-rosbag)";
  }
  const fs::path dir = fs::path(::testing::TempDir()) / "pliant_ros_node";
  fs::remove_all(dir);
  fs::create_directories(dir);
  // The reference: the bag's log, as `pliant import` writes it, through `pliant filter`.
  io::WriteLog((dir / "bag.csv").string(), ReadCrtkBag(kBag, {"PSM2"}));
  const std::string filter = std::string(PLIANT_CLI) + " filter --quiet --params " + kParams +
                             " " + (dir / "bag.csv").string() + " -o " +
                             (dir / "filtered.csv").string() + " > /dev/null";
  ASSERT_EQ(std::system(filter.c_str()), 0);
  const io::Log expected = io::ReadLog((dir / "filtered.csv").string());

  const std::string port = std::to_string(FreePort());
  ::setenv("ROS_MASTER_URI", ("http://127.0.0.1:" + port).c_str(), 1);
  ::setenv("ROS_IP", "127.0.0.1", 1);
  ::setenv("ROS_HOME", dir.c_str(), 1);
  ::setenv("ROS_LOG_DIR", dir.c_str(), 1);
  const pid_t roscore = Spawn({"roscore", "-p", port}, dir / "roscore.log");
  ::ros::M_string remappings;
  ::ros::init(remappings, "pliant_ros_test", ::ros::init_options::NoSigintHandler);
  ASSERT_TRUE(WaitFor([] { return ::ros::master::check(); }, std::chrono::seconds(30)))
      << "roscore did not start on port " << port;

  const pid_t node = Spawn({PLIANT_ROS_NODE, "_arm:=PSM2", "_params_file:=" + kParams,
                            "_queue_size:=100000"},
                           dir / "node.log");
  Received received;
  ::ros::NodeHandle handle;
  auto keep = [&received](std::vector<sensor_msgs::JointState>* into) {
    return [&received, into](const sensor_msgs::JointState::ConstPtr& m) {
      const std::lock_guard<std::mutex> lock(received.mutex);
      into->push_back(*m);
    };
  };
  ::ros::Subscriber corrected = handle.subscribe<sensor_msgs::JointState>(
      "/PSM2/pliant/measured_js", 100000, keep(&received.corrected));
  ::ros::Subscriber sd = handle.subscribe<sensor_msgs::JointState>(
      "/PSM2/pliant/measured_js_sd", 100000, keep(&received.sd));
  ::ros::AsyncSpinner spinner(1);
  spinner.start();
  const bool node_up = WaitFor(
      [&] { return corrected.getNumPublishers() > 0 && sd.getNumPublishers() > 0; },
      std::chrono::seconds(30));

  // -d 3: rosbag waits after advertising, so the node is connected before the
  // first message (a missed first message would move every t).
  const pid_t player = Spawn({"rosbag", "play", "-q", "-d", "3", "-r", "4", kBag, "--topics",
                              "/PSM2/measured_js"},
                             dir / "rosbag.log");
  int player_status = -1;
  const bool played = node_up && WaitFor([&] { return ::waitpid(player, &player_status, WNOHANG) ==
                                                      player; },
                                         std::chrono::seconds(60));
  if (!played) Stop(player, std::chrono::seconds(5));
  // The last messages are in flight for a moment after the player exits.
  std::size_t count = 0;
  WaitFor(
      [&] {
        const std::lock_guard<std::mutex> lock(received.mutex);
        const bool settled = received.corrected.size() == count && count > 0;
        count = received.corrected.size();
        return settled && received.sd.size() == count;
      },
      std::chrono::seconds(20));
  spinner.stop();
  ::ros::shutdown();
  Stop(node, std::chrono::seconds(10));
  Stop(roscore, std::chrono::seconds(15));
  ASSERT_TRUE(node_up) << "pliant_ros did not advertise; its log: " << dir / "node.log";
  ASSERT_TRUE(played) << "rosbag play did not finish in 60 s";

  const auto& h = expected.header;
  const int q1 = h.Index("q1_corr"), q2 = h.Index("q2_corr"), q3 = h.Index("q3");
  const int sd1 = h.Index("q1_sd"), sd2 = h.Index("q2_sd");
  ASSERT_EQ(received.corrected.size(), expected.Rows()) << "every measured_js is filtered";
  ASSERT_EQ(received.sd.size(), expected.Rows());
  for (std::size_t r = 0; r < expected.Rows(); ++r) {
    const double* row = &expected.values[r * expected.Columns()];
    const auto& m = received.corrected[r];
    ASSERT_EQ(m.position.size(), 6u);
    // Tolerance 0: the node runs the same filter on the same doubles, and the
    // log's numbers read back bit-exact.
    EXPECT_EQ(m.position[0], row[q1]) << "message " << r;
    EXPECT_EQ(m.position[1], row[q2]) << "message " << r;
    EXPECT_EQ(m.position[2], row[q3]) << "message " << r;
    EXPECT_EQ(received.sd[r].position[0], row[sd1]) << "message " << r;
    EXPECT_EQ(received.sd[r].position[1], row[sd2]) << "message " << r;
    EXPECT_EQ(received.sd[r].header.stamp, m.header.stamp);
  }
}

}  // namespace
}  // namespace pliant::ros
