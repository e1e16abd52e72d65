// What the ROS node runs, built before the node from its ~ parameters and handed to it, as
// cartographer_ros builds its Node from NodeOptions and a MapBuilderInterface made outside
// (cartographer_ros/node_main.cc): the world file loaded, the Simulator on it, the step profile.
// The node (ros/sim_node.h) owns the ROS side only: robots' bridges, publishers, services.
#ifndef TIANRACER_SIM_ROS_SIM_NODE_CORE_H
#define TIANRACER_SIM_ROS_SIM_NODE_CORE_H

#include <memory>
#include <string>
#include <utility>
#include <vector>

#include <ros/ros.h>

#include "tianracer_sim/common/step_profile.h"
#include "tianracer_sim/ros/params.h"
#include "tianracer_sim/simulator/simulator.h"
#include "tianracer_sim/world/world.h"

namespace tianracer_sim {

struct SimNodeCore {
  NodeParams params;
  /// How the world file was loaded (ROS packages, ~strict_world); spawn_sdf_model loads the
  /// same way.
  WorldLoadOptions world_options;
  /// ~profile: every part of the step timed, the node's rows first in the loop's order
  /// (makeNodeProfile). Null when not profiling. Outlives `sim`, which times into it.
  std::unique_ptr<StepProfile> profile;
  /// The world's Simulator; its world models' sensors publish once the node attaches them
  /// (Simulator::attachWorldSensors).
  std::unique_ptr<Simulator> sim;
  /// The pace: ~real_time_factor, else the world's.
  double real_time_factor = 1.0;
  /// Start-up's parts so far, (what, wall ms): the node goes on counting.
  std::vector<std::pair<std::string, double>> startup;
};

/// Reads the node's ~ parameters from `pnh`, loads the world they name and builds the
/// Simulator on it. Throws std::exception naming the parameter or the world file.
SimNodeCore makeSimNodeCore(const ros::NodeHandle& pnh);

/// The node loop's rows of the ~profile table.
struct NodeProfileRows {
  int step = -1, callbacks = -1, status = -1, commands = -1, contact_msgs = -1, clock = -1;
  int gazebo_states = -1, lockstep = -1;
};

/// Registers the node loop's rows in `p` in the order the loop runs them, or finds them when
/// they are there (row() keeps the first registration's place).
NodeProfileRows nodeProfileRows(StepProfile& p);

/// The ~profile table's StepProfile with the node loop's rows first (nodeProfileRows): the
/// Simulator, robots' bridges and sensors add theirs as they are set up.
std::unique_ptr<StepProfile> makeNodeProfile();

/// Logs each distinct warning once (loaders repeat theirs for every robot and spawn).
void warnOnceOnRosout(const std::string& text);

}  // namespace tianracer_sim

#endif  // TIANRACER_SIM_ROS_SIM_NODE_CORE_H
