// Bumper states (plugins/bumper/bumper.h) -> gazebo_msgs/ContactsState.
#ifndef TIANRACER_SIM_ROS_BUMPER_MSGS_H
#define TIANRACER_SIM_ROS_BUMPER_MSGS_H

#include <string>
#include <vector>

#include <gazebo_msgs/ContactsState.h>
#include <ros/time.h>

#include "tianracer_sim/plugins/bumper/bumper.h"

namespace tianracer_sim {

/// header (stamp, frame_id) and one ContactState per pair: wrenches (force only), their
/// total, positions, normals and depths; info names the pair.
void toContactsState(const std::vector<BumperState>& states, const ros::Time& stamp,
                     const std::string& frame_id, gazebo_msgs::ContactsState* msg);

}  // namespace tianracer_sim

#endif  // TIANRACER_SIM_ROS_BUMPER_MSGS_H
