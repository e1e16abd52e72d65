// Reading the node's parameters: numbers, name lists, spawn poses, each with an error that
// names the parameter and the value.
#ifndef TIANRACER_SIM_ROS_PARAMS_H
#define TIANRACER_SIM_ROS_PARAMS_H

#include <optional>
#include <string>
#include <vector>

#include <Eigen/Geometry>
#include <ros/node_handle.h>

#include "tianracer_sim/common/text.h"

namespace tianracer_sim {

/// The node's own parameters (sim_node.h lists them), read in one place. Unset optionals take
/// the world's <physics> values.
struct NodeParams {
  std::string world = "empty";
  bool strict_world = false;
  std::optional<double> max_step_size, real_time_factor;
  bool paused = false;
  double clock_rate = 200.0;
  double ground_truth_rate = 50.0;
  double status_period = 5.0;
  int seed = 0;
  bool diagnostics = true;
  bool step_services = true;
  bool enable_ros_network = true;
  // where gazebo_ros's topics and services are: its node's private namespace ("~" in
  // gazebo_ros_api_plugin), which the gzserver stand-in passes; /gazebo for our own launches
  std::string gazebo_namespace = "/gazebo";
  std::optional<double> gazebo_states_rate;
};

/// Reads ~world ... ~step_services from `pnh`. Throws naming a parameter that is not a number.
NodeParams readNodeParams(const ros::NodeHandle& pnh);

/// The step and the real-time factor in force (the parameters' or the world's). Throws naming
/// the parameter for a step outside (0, 0.1] s or a factor below 0.
void checkPace(double max_step_size, double real_time_factor);

/// A number (int or double); `fallback` when unset. Throws naming the parameter otherwise.
double getDouble(const ros::NodeHandle& nh, const std::string& key, double fallback);

/// A list of names or a space-separated string; *given says whether the parameter is set.
std::vector<std::string> getNameList(const ros::NodeHandle& nh, const std::string& key, bool* given);

/// ~x ~y ~z ~roll ~pitch ~yaw of `rp`: base_link's pose; z "auto" (or unset) sets *auto_z.
/// Throws naming the parameters for a pose out of checkModelState's bounds.
Eigen::Isometry3d getSpawnPose(const ros::NodeHandle& rp, bool* auto_z);

}  // namespace tianracer_sim

#endif  // TIANRACER_SIM_ROS_PARAMS_H
