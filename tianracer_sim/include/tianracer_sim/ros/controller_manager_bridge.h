// controller_manager's ROS interface for one robot, over the simulator's controllers:
// <robot ns>/controller_manager/{list_controllers, list_controller_types, load_controller,
// unload_controller, switch_controller, reload_controller_libraries} with
// controller_manager_msgs types, as gazebo_ros_control's ControllerManager advertises them
// (ros_control noetic-devel, controller_manager/src/controller_manager.cpp: same rules, same
// error texts, logged with ROS_ERROR). The controllers run in the simulation; a switch takes
// effect at once, between two steps (there is no real-time loop to wait for).
#ifndef TIANRACER_SIM_ROS_CONTROLLER_MANAGER_BRIDGE_H
#define TIANRACER_SIM_ROS_CONTROLLER_MANAGER_BRIDGE_H

#include <functional>
#include <string>
#include <vector>

#include <controller_manager_msgs/ListControllerTypes.h>
#include <controller_manager_msgs/ListControllers.h>
#include <controller_manager_msgs/LoadController.h>
#include <controller_manager_msgs/ReloadControllerLibraries.h>
#include <controller_manager_msgs/SwitchController.h>
#include <controller_manager_msgs/UnloadController.h>
#include <ros/ros.h>

#include "tianracer_sim/simulator/simulator.h"

namespace tianracer_sim {

class ControllerManagerBridge {
 public:
  /// `robot_nh`: the robot's ros_control namespace, on the node's callback queue (services run
  /// between steps). A controller's parameters are read from `control_ns`/<name> (the robot's
  /// namespace unless ~control_namespace moves them). `changed` runs after each load, unload
  /// or switch, so that the node follows (command topics, joint_states).
  ControllerManagerBridge(ros::NodeHandle robot_nh, std::string control_ns, Simulator& sim,
                          ModelId robot, std::function<void()> changed);
  ControllerManagerBridge(const ControllerManagerBridge&) = delete;
  ControllerManagerBridge& operator=(const ControllerManagerBridge&) = delete;

 private:
  bool onList(controller_manager_msgs::ListControllers::Request&,
              controller_manager_msgs::ListControllers::Response&);
  bool onListTypes(controller_manager_msgs::ListControllerTypes::Request&,
                   controller_manager_msgs::ListControllerTypes::Response&);
  bool onLoad(controller_manager_msgs::LoadController::Request&,
              controller_manager_msgs::LoadController::Response&);
  bool onUnload(controller_manager_msgs::UnloadController::Request&,
                controller_manager_msgs::UnloadController::Response&);
  bool onSwitch(controller_manager_msgs::SwitchController::Request&,
                controller_manager_msgs::SwitchController::Response&);
  bool onReload(controller_manager_msgs::ReloadControllerLibraries::Request&,
                controller_manager_msgs::ReloadControllerLibraries::Response&);

  bool load(const std::string& name);
  bool unload(const std::string& name);
  bool switchControllers(const std::vector<std::string>& start,
                         const std::vector<std::string>& stop, int strictness);

  std::string control_ns_;
  const tianracer_control::ControllerSet& controllers() const;

  Simulator& sim_;
  ModelId robot_;
  std::function<void()> changed_;
  std::vector<ros::ServiceServer> services_;
};

}  // namespace tianracer_sim

#endif  // TIANRACER_SIM_ROS_CONTROLLER_MANAGER_BRIDGE_H
