// Which controllers a robot gets and where their parameters are read: the ros_control YAML
// loaded on the parameter server (controller_manager's spawner is given a list; our default is
// every controller under the namespace). The specs themselves are read by tianracer_control's
// ROS adapter.
#ifndef TIANRACER_SIM_ROS_CONTROLLER_PARAMS_H
#define TIANRACER_SIM_ROS_CONTROLLER_PARAMS_H

#include <string>
#include <vector>

#include <ros/node_handle.h>

namespace tianracer_sim {

/// Names of the controllers defined under `ns` (every struct member with a `type` key), sorted.
std::vector<std::string> listControllers(const ros::NodeHandle& ns);

/// The top-level keys of a ros_control YAML file (~control_config: what `rosparam load` put at
/// the launch file's namespace), and those that define controllers (a dictionary with at least
/// one member that has a `type`).
struct ControlConfigKeys {
  std::string file;
  std::vector<std::string> keys;
  std::vector<std::string> with_controllers;
  std::string error;  // the file could not be read or is no YAML dictionary ("" = fine)
};
ControlConfigKeys readControlConfigKeys(const std::string& file);

/// Where a robot's controllers are read when ~control_namespace is not given: its ros_control
/// namespace when controllers are defined there; else the one top-level key of the YAML that
/// defines controllers (the shipped YAML is keyed `tianracer` whatever the car is called), as a
/// name relative to the node's namespace; else the robot's namespace (where none are found).
std::string chooseControlNamespace(const std::string& robot_ns, bool robot_ns_has_controllers,
                                   const ControlConfigKeys& config);

/// chooseControlNamespace() from the parameter server and ~control_config (in `rp`, the robot's
/// own parameters; read into *config); logs the choice when it is not the robot's namespace.
std::string defaultControlNamespace(const ros::NodeHandle& rp, const std::string& robot_ns,
                                    ControlConfigKeys* config);

/// The start-up warning for a robot with gazebo_ros_control that gets no controller: names the
/// namespace searched and the YAML's top-level keys, and what to pass.
std::string noControllersWarning(const std::string& robot, const std::string& searched,
                                 const ControlConfigKeys& config);

}  // namespace tianracer_sim

#endif  // TIANRACER_SIM_ROS_CONTROLLER_PARAMS_H
