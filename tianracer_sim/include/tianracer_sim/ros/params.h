// Reading the node's parameters: numbers, name lists, spawn poses, each with an error that
// names the parameter and the value.
#ifndef TIANRACER_SIM_ROS_PARAMS_H
#define TIANRACER_SIM_ROS_PARAMS_H

#include <string>
#include <vector>

#include <Eigen/Geometry>
#include <ros/node_handle.h>

namespace tianracer_sim {

/// "/a/b/" -> "a/b".
std::string trimSlashes(std::string s);

/// A number (int or double); `fallback` when unset. Throws naming the parameter otherwise.
double getDouble(const ros::NodeHandle& nh, const std::string& key, double fallback);

/// A list of names or a space-separated string; *given says whether the parameter is set.
std::vector<std::string> getNameList(const ros::NodeHandle& nh, const std::string& key, bool* given);

/// ~x ~y ~z ~roll ~pitch ~yaw of `rp`: base_link's pose; z "auto" (or unset) sets *auto_z.
/// Throws naming the parameters for a pose out of checkModelState's bounds.
Eigen::Isometry3d getSpawnPose(const ros::NodeHandle& rp, bool* auto_z);

}  // namespace tianracer_sim

#endif  // TIANRACER_SIM_ROS_PARAMS_H
