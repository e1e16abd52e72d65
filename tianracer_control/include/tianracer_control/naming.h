// The one naming module for what the simulator publishes: TF frame names with a tf_prefix and
// topic names in a namespace, resolved the way gazebo_ros plugins and robot_state_publisher do
// (tf::resolve, ros::names::resolve), so that several robots of one model share one TF tree and
// one ROS graph. Used by the sensors (tianracer_sim/plugins/), the node and the odometry node.
#ifndef TIANRACER_CONTROL_NAMING_H
#define TIANRACER_CONTROL_NAMING_H

#include <string>

namespace tianracer_control {

/// `prefix/frame`, without leading slashes (tf2 frame ids have none):
///   resolveFrame("", "base_link")             == "base_link"
///   resolveFrame("tianracer_02", "base_link") == "tianracer_02/base_link"
///   resolveFrame("/tianracer_02/", "odom")    == "tianracer_02/odom"
/// A frame written with a leading '/' is absolute and keeps no prefix: "/map" -> "map".
std::string resolveFrame(const std::string& prefix, const std::string& frame);

/// Joins a namespace and a name as ros::names::resolve would: an absolute name is kept,
/// a relative one is appended to the namespace (which gets a leading '/'), '//' collapsed:
///   resolveTopic("rrbot/camera1", "image_raw") == "/rrbot/camera1/image_raw"
///   resolveTopic("", "scan")                   == "/scan"
///   resolveTopic("tianracer", "/clock")        == "/clock"
std::string resolveTopic(const std::string& ns, const std::string& name);

}  // namespace tianracer_control

#endif  // TIANRACER_CONTROL_NAMING_H
