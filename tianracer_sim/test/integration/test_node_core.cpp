// rostest (node_core.test): the node runs a core its caller built (ros/sim_node_core.h), as
// cartographer_ros's Node runs a map builder made outside it:
//   - a SimNode without a Simulator is refused; makeSimNodeCore names a world file it cannot read;
//   - a Simulator built here from a world file (no ~world parameter) runs under the node: its
//     world model's lidar publishes on its plugin's topic and sees the target, /clock moves,
//     and /gazebo/model_states lists the world's models.
// Sim time: the scan is awaited by count; wall time only bounds the waits.
#include <gtest/gtest.h>

#include <algorithm>
#include <atomic>
#include <chrono>
#include <memory>
#include <string>
#include <thread>

#include <gazebo_msgs/ModelStates.h>
#include <ros/ros.h>
#include <rosgraph_msgs/Clock.h>
#include <sensor_msgs/LaserScan.h>

#include "tianracer_sim/ros/sim_node.h"
#include "tianracer_sim/ros/sim_node_core.h"
#include "tianracer_sim/world/world.h"

namespace tianracer_sim {
namespace {

const std::string kWorld = std::string(TEST_DATA_DIR) + "/worlds/world_model_sensors.world";

template <typename Done>
bool waitWall(Done done, double seconds) {
  const auto end = std::chrono::steady_clock::now() + std::chrono::duration<double>(seconds);
  while (!done()) {
    if (std::chrono::steady_clock::now() > end) return false;
    std::this_thread::sleep_for(std::chrono::milliseconds(10));
  }
  return true;
}

TEST(NodeCore, ANodeWithoutASimulatorIsRefused) {
  ros::NodeHandle pnh("~");
  try {
    SimNode node(ros::NodeHandle(), pnh, SimNodeCore{});
    FAIL() << "a node without a Simulator was made";
  } catch (const std::invalid_argument& e) {
    EXPECT_STREQ(e.what(), "SimNode: no Simulator given");
  }
}

TEST(NodeCore, TheFactoryNamesAWorldFileItCannotRead) {
  ros::NodeHandle pnh("~factory");
  pnh.setParam("world", "/nonexistent/dir/none.world");
  try {
    (void)makeSimNodeCore(pnh);
    FAIL() << "a core on a missing world file was made";
  } catch (const std::exception& e) {
    EXPECT_NE(std::string(e.what()).find("/nonexistent/dir/none.world"), std::string::npos)
        << e.what();
  }
}

// Last: it shuts roscpp down.
TEST(NodeCore, RunsASimulatorBuiltOutsideTheNode) {
  ros::NodeHandle pnh("~");
  pnh.setParam("robots", std::vector<std::string>{});  // the world alone, as gzserver x.world
  SimNodeCore core;
  core.params = readNodeParams(pnh);
  core.real_time_factor = 0.0;  // as fast as it goes
  core.sim = std::make_unique<Simulator>(loadWorldFile(kWorld), SimulatorOptions{});

  ros::NodeHandle nh;
  std::atomic<int> scans{0};
  std::atomic<float> ahead{0.0f};
  std::atomic<double> clock{0.0};
  std::atomic<bool> listed{false};
  ros::Subscriber scan_sub = nh.subscribe<sensor_msgs::LaserScan>(
      "/post/scan", 10, [&](const sensor_msgs::LaserScan::ConstPtr& m) {
        if (m->ranges.size() == 181) ahead = m->ranges[90];
        ++scans;
      });
  ros::Subscriber clock_sub = nh.subscribe<rosgraph_msgs::Clock>(
      "/clock", 10, [&](const rosgraph_msgs::Clock::ConstPtr& m) { clock = m->clock.toSec(); });
  ros::Subscriber states_sub = nh.subscribe<gazebo_msgs::ModelStates>(
      "/gazebo/model_states", 10, [&](const gazebo_msgs::ModelStates::ConstPtr& m) {
        const auto has = [&](const std::string& n) {
          return std::find(m->name.begin(), m->name.end(), n) != m->name.end();
        };
        listed = has("sensor_post") && has("target") && has("faller");
      });
  ros::AsyncSpinner spinner(1);  // the test's subscriptions; the node serves its own queue
  spinner.start();

  SimNode node(nh, pnh, std::move(core));
  std::thread run([&] { node.run(); });
  const bool got = waitWall([&] { return scans >= 5 && listed && clock > 0.2; }, 60.0);
  ros::shutdown();
  run.join();
  ASSERT_TRUE(got) << scans << " scans, model_states listed " << listed << ", clock " << clock;
  // The post's lidar, 0.5 m up at the origin, sees the target's near face 2.5 m ahead.
  EXPECT_NEAR(ahead, 2.5, 0.05);
}

}  // namespace
}  // namespace tianracer_sim

int main(int argc, char** argv) {
  testing::InitGoogleTest(&argc, argv);
  ros::init(argc, argv, "test_node_core");
  return RUN_ALL_TESTS();
}
