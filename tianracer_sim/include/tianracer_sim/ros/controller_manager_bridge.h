// controller_manager's ROS interface for one robot, over the simulator's controllers:
// <robot ns>/controller_manager/{list_controllers, list_controller_types, load_controller,
// unload_controller, switch_controller, reload_controller_libraries} with
// controller_manager_msgs types, as gazebo_ros_control's ControllerManager advertises them
// (ros_control noetic-devel, controller_manager/src/controller_manager.cpp: same rules, same
// error texts, logged with ROS_ERROR). The controllers run in the simulation; a switch takes
// effect at once, between two steps (there is no real-time loop to wait for).
#ifndef TIANRACER_SIM_ROS_CONTROLLER_MANAGER_BRIDGE_H
#define TIANRACER_SIM_ROS_CONTROLLER_MANAGER_BRIDGE_H

#include <cstdint>
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

#include "tianracer_sim/ros/service_advertiser.h"
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
  using ListControllers = controller_manager_msgs::ListControllers;
  using ListControllerTypes = controller_manager_msgs::ListControllerTypes;
  using LoadController = controller_manager_msgs::LoadController;
  using UnloadController = controller_manager_msgs::UnloadController;
  using SwitchController = controller_manager_msgs::SwitchController;
  using ReloadLibraries = controller_manager_msgs::ReloadControllerLibraries;
  bool onList(ListControllers::Request&, ListControllers::Response&);
  bool onListTypes(ListControllerTypes::Request&, ListControllerTypes::Response&);
  bool onLoad(LoadController::Request&, LoadController::Response&);
  bool onUnload(UnloadController::Request&, UnloadController::Response&);
  bool onSwitch(SwitchController::Request&, SwitchController::Response&);
  bool onReload(ReloadLibraries::Request&, ReloadLibraries::Response&);
  /// A load, unload or switch answered: res.ok = ok; the node follows when it succeeded.
  bool answer(bool ok, uint8_t* res_ok);

  bool load(const std::string& name);
  bool unload(const std::string& name);
  bool switchControllers(const std::vector<std::string>& start,
                         const std::vector<std::string>& stop, int strictness);

  std::string control_ns_;
  /// The robot, or ControllerError once it has left the world.
  SimRobot& robot() const;
  const tianracer_control::ControllerSet& controllers() const;

  Simulator& sim_;
  ModelId robot_;
  std::function<void()> changed_;
  std::vector<ros::ServiceServer> services_;
};

}  // namespace tianracer_sim

#endif  // TIANRACER_SIM_ROS_CONTROLLER_MANAGER_BRIDGE_H
