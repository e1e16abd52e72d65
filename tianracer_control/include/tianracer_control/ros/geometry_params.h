// ROS parameters -> Ackermann geometry and joint names, shared by the cmd_vel and odometry nodes.
#ifndef TIANRACER_CONTROL_ROS_GEOMETRY_PARAMS_H
#define TIANRACER_CONTROL_ROS_GEOMETRY_PARAMS_H

#include <ros/node_handle.h>

#include "tianracer_control/ackermann.h"
#include "tianracer_control/urdf_geometry.h"

namespace tianracer_control {

/// ~left_steering_hinge_joint, ~right_steering_hinge_joint, ~left_rear_wheel_joint,
/// ~right_rear_wheel_joint (defaults: the seed's names).
AckermannJointNames loadJointNames(const ros::NodeHandle& pnh);

/// What the nodes know about the car: its joint and base link names as the model writes them,
/// and its geometry.
struct AckermannSetup {
  AckermannJointNames joints;
  std::string base_frame;  // the model's base link, e.g. "car1/base_link"
  std::string prefix;      // the prefix its joint names share, e.g. "car1/", or ""
  AckermannGeometry geometry;
};

/// Reads robot_description (the parameter named by ~robot_description_param, default
/// "robot_description", looked up with searchParam from nh's namespace upwards) and finds the
/// joints named by loadJointNames() and ~base_frame (default "base_link") in it, prefixed or
/// not (findModelNames). Resolves the geometry: ~wheelbase, ~hinge_separation, ~wheel_radius,
/// ~rear_track, ~max_steering_angle, ~rear_axle_x where given; otherwise from the URDF,
/// positions in the base link, relative mesh paths against ~model_dir; otherwise the defaults. Logs each name found under another
/// name, each value with its source once, and every warning. Throws AckermannError for a
/// non-numeric parameter, an unparsable robot_description or an invalid geometry.
AckermannSetup loadAckermannSetup(const ros::NodeHandle& nh, const ros::NodeHandle& pnh);

/// Reads a double parameter that may be written as an int; throws AckermannError naming it if
/// it is present but not a number. Returns false when absent.
bool getNumberParam(const ros::NodeHandle& pnh, const std::string& key, double* value);

}  // namespace tianracer_control

#endif  // TIANRACER_CONTROL_ROS_GEOMETRY_PARAMS_H
