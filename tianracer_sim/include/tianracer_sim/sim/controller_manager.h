// ControllerManager: the one owner of the robots' controllers, as ros_control's
// controller_manager is (ros-controls/ros_control noetic-devel,
// controller_manager/src/controller_manager.cpp): it loads a robot's configured controllers
// when the robot is added, loads, unloads and switches them by name (the load_controller,
// unload_controller and switch_controller services, the spawner, Python), runs the running
// ones every control period, restarts them on a reset, and keeps which joints are written
// (a robot's claimed handles). Reading and writing the joints is the hardware's business
// (Simulation, as DefaultRobotHWSim's readSim/writeSim): the manager is given the read.
// ROS-free: the ROS services (ros/controller_manager_bridge.h) and the Python env call it.
#ifndef TIANRACER_SIM_SIM_CONTROLLER_MANAGER_H
#define TIANRACER_SIM_SIM_CONTROLLER_MANAGER_H

#include <functional>
#include <string>
#include <vector>

#include <tianracer_control/controller_set.h>

#include "tianracer_sim/physics/world.h"

namespace tianracer_sim {

struct SimRobot;

class ControllerManager {
 public:
  /// `read` fills a robot's handles from its joints (the hardware's read).
  ControllerManager(PhysicsWorld& physics, WarningSink warn,
                    std::function<void(SimRobot&)> read);

  /// A robot entering the simulation: its controllers, loaded and started in order (a
  /// controller that fails throws tianracer_control::ControllerError naming it), and its
  /// claimed joints. Joints no controller writes stay free (no motor holding them).
  void attach(SimRobot& robot, const std::vector<tianracer_control::ControllerSpec>& specs);

  /// controller_manager's load_controller: a controller, stopped (its joints must exist and be
  /// free of other loaded controllers' claims as controller_manager checks them). Throws
  /// tianracer_control::ControllerError with controller_manager's text; nothing changes then.
  tianracer_control::Controller& load(SimRobot& robot,
                                      const tianracer_control::ControllerSpec& spec);
  /// unload_controller: a stopped controller (ControllerError otherwise).
  void unload(SimRobot& robot, const std::string& name);
  /// switch_controller: stops, then starts, by name (ControllerSet's rules for strictness). A
  /// starting controller reads the current joint state first. Afterwards exactly the joints of
  /// running controllers are written; a joint whose controller stopped is free again (in
  /// Gazebo, DefaultRobotHWSim keeps applying its last command).
  void switchControllers(SimRobot& robot, const std::vector<std::string>& start,
                         const std::vector<std::string>& stop,
                         tianracer_control::Strictness strictness);
  /// The command of a controller (as its /command topic sets it). False for an unknown
  /// controller, one without a command, or a non-finite value (the previous command stays).
  bool setCommand(SimRobot& robot, const std::string& controller, double value);

  /// The running controllers' update over one control period (after the hardware's read).
  void update(SimRobot& robot);
  /// A reset (reset_simulation, reset_world): commands to 0, controllers restarted from the
  /// current joint state (the caller reads before and writes after).
  void restart(SimRobot& robot);

 private:
  /// claimed = written by a running controller; a joint no longer claimed is freed.
  void updateClaims(SimRobot& robot);
  WarningSink robotWarnings(const SimRobot& robot) const;

  PhysicsWorld& physics_;
  WarningSink warn_;
  std::function<void(SimRobot&)> read_;
};

}  // namespace tianracer_sim

#endif  // TIANRACER_SIM_SIM_CONTROLLER_MANAGER_H
