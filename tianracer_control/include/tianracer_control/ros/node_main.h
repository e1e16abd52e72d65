// The main() of a node whose work is one object made from its node handles (cmd_vel_node,
// wheel_odometry_node).
#ifndef TIANRACER_CONTROL_ROS_NODE_MAIN_H
#define TIANRACER_CONTROL_ROS_NODE_MAIN_H

#include <exception>

#include <ros/ros.h>

namespace tianracer_control {

/// ros::init as `name`, makes Node(nh, private nh), spins until shutdown. What the constructor
/// throws (a bad parameter) is logged fatal and the node exits 1.
template <class Node>
int runNode(int argc, char** argv, const char* name) {
  ros::init(argc, argv, name);
  try {
    Node node{ros::NodeHandle(), ros::NodeHandle("~")};
    ros::spin();
  } catch (const std::exception& e) {
    ROS_FATAL("%s", e.what());
    return 1;
  }
  return 0;
}

}  // namespace tianracer_control

#endif  // TIANRACER_CONTROL_ROS_NODE_MAIN_H
