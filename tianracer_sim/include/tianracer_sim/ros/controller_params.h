// Which controllers a ros_control YAML defines (controller_manager's spawner is given the list;
// our default is every controller under the namespace). The specs themselves are read by
// tianracer_control's ROS adapter.
#ifndef TIANRACER_SIM_ROS_CONTROLLER_PARAMS_H
#define TIANRACER_SIM_ROS_CONTROLLER_PARAMS_H

#include <string>
#include <vector>

#include <ros/node_handle.h>

namespace tianracer_sim {

/// Names of the controllers defined under `ns` (every struct member with a `type` key), sorted.
std::vector<std::string> listControllers(const ros::NodeHandle& ns);


}  // namespace tianracer_sim

#endif  // TIANRACER_SIM_ROS_CONTROLLER_PARAMS_H
