// ROS side of the controllers: parameter server -> ControllerSpec, and each loaded
// controller's ROS side (controller_ros.h: its topics). Used by the simulator node.
#ifndef TIANRACER_CONTROL_ROS_CONTROLLER_ADAPTER_H
#define TIANRACER_CONTROL_ROS_CONTROLLER_ADAPTER_H

#include <memory>
#include <string>
#include <vector>

#include <ros/node_handle.h>
#include <xmlrpcpp/XmlRpcValue.h>

#include "tianracer_control/joint_controllers.h"
#include "tianracer_control/ros/controller_ros.h"

namespace tianracer_control {

/// A parameter server value as a tree (XmlRpcValue's kinds).
ParamValue toParamValue(XmlRpc::XmlRpcValue v);

/// One controller's parameter tree (e.g. the value of /tianracer/joint_state_controller) ->
/// spec: its type, and the whole tree for the controller class to read. Throws ControllerError
/// naming the controller when the tree is not a struct or the type is not a string (the class
/// checks the kinds of its own keys when it is built).
ControllerSpec toControllerSpec(const std::string& name, const XmlRpc::XmlRpcValue& params);

/// Reads <ns>/<name> for each name (the list a spawner would get). Throws ControllerError
/// ("controller 'x': no parameters at /tianracer/x") when one is absent.
std::vector<ControllerSpec> loadControllerSpecs(const ros::NodeHandle& ns,
                                                const std::vector<std::string>& names);

/// The ROS sides (controller_ros.h) of a robot's loaded controllers, made for every loaded
/// controller whose type registered one: e.g. <ns>/<controller>/command (std_msgs/Float64) of
/// the single-joint controllers, <ns>/<controller>/cmd_vel of diff_drive_controller. Made anew
/// when the controllers change (load, unload). Commands are buffered under a mutex and applied
/// by apply(), which the simulation loop calls before ControllerSet::update(): callbacks may run
/// on any spinner thread, the controllers are only touched by the loop. NaN/inf commands are
/// dropped with a throttled warning naming the controller; the previous command stays.
class ControllerCommandSubscribers {
 public:
  /// `previous`: the sides made before the controllers changed; the sides of the controllers
  /// still loaded are taken over from it (their subscriptions, services and pending commands
  /// stay), so that it must be made after every load or unload.
  ControllerCommandSubscribers(ros::NodeHandle ns, ControllerSet& controllers,
                               ControllerCommandSubscribers* previous = nullptr);
  ~ControllerCommandSubscribers();
  ControllerCommandSubscribers(const ControllerCommandSubscribers&) = delete;
  ControllerCommandSubscribers& operator=(const ControllerCommandSubscribers&) = delete;

  /// Hands the commands received since the last call to their controllers.
  void apply();
  /// What the controllers produced since the last call (odom, tf, ...), at sim time t.
  void publish(double t);
  /// Drops commands not yet applied (sim reset).
  void clear();
  /// The command topics, e.g. "/tianracer/left_rear_wheel_velocity_controller/command".
  std::vector<std::string> topics() const;

 private:
  std::vector<std::unique_ptr<ControllerRosSide>> sides_;
  std::vector<const Controller*> owners_;  // the controller of each side
};

}  // namespace tianracer_control

#endif  // TIANRACER_CONTROL_ROS_CONTROLLER_ADAPTER_H
