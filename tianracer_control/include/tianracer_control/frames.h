// TF frame names with a tf_prefix, resolved the way gazebo_ros plugins and
// robot_state_publisher do (tf::resolve): several robots of one model in one TF tree.
#ifndef TIANRACER_CONTROL_FRAMES_H
#define TIANRACER_CONTROL_FRAMES_H

#include <string>

namespace tianracer_control {

/// `prefix/frame`, without leading slashes (tf2 frame ids have none):
///   resolveFrame("", "base_link")             == "base_link"
///   resolveFrame("tianracer_02", "base_link") == "tianracer_02/base_link"
///   resolveFrame("/tianracer_02/", "odom")    == "tianracer_02/odom"
/// A frame written with a leading '/' is absolute and keeps no prefix: "/map" -> "map".
std::string resolveFrame(const std::string& prefix, const std::string& frame);

}  // namespace tianracer_control

#endif  // TIANRACER_CONTROL_FRAMES_H
