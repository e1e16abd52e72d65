// ROS side of the joint controllers: parameter server -> ControllerSpec, and the
// /<ns>/<controller>/command topics -> Controller::setCommand(). Used by the simulator node.
#ifndef TIANRACER_CONTROL_ROS_CONTROLLER_ADAPTER_H
#define TIANRACER_CONTROL_ROS_CONTROLLER_ADAPTER_H

#include <map>
#include <mutex>
#include <string>
#include <vector>

#include <ros/node_handle.h>
#include <ros/subscriber.h>
#include <std_msgs/Float64.h>
#include <xmlrpcpp/XmlRpcValue.h>

#include "tianracer_control/joint_controllers.h"

namespace tianracer_control {

/// One controller's parameter tree (e.g. the value of /tianracer/joint_state_controller) ->
/// spec: its type, and the whole tree for the controller class to read. Throws ControllerError
/// naming the controller when the tree is not a struct or the type is not a string (the class
/// checks the kinds of its own keys when it is built).
ControllerSpec toControllerSpec(const std::string& name, const XmlRpc::XmlRpcValue& params);

/// Reads <ns>/<name> for each name (the list a spawner would get). Throws ControllerError
/// ("controller 'x': no parameters at /tianracer/x") when one is absent.
std::vector<ControllerSpec> loadControllerSpecs(const ros::NodeHandle& ns,
                                                const std::vector<std::string>& names);

/// Subscribes <ns>/<controller>/command (std_msgs/Float64) for every controller with a
/// command. Messages are buffered under a mutex and applied by apply(), which the simulation
/// loop calls before ControllerSet::update(): callbacks may run on any spinner thread, the
/// controllers are only touched by the loop. NaN/inf commands are dropped with a throttled
/// warning naming the controller; the previous command stays.
class ControllerCommandSubscribers {
 public:
  ControllerCommandSubscribers(ros::NodeHandle ns, ControllerSet& controllers);
  ControllerCommandSubscribers(const ControllerCommandSubscribers&) = delete;
  ControllerCommandSubscribers& operator=(const ControllerCommandSubscribers&) = delete;

  /// Hands the commands received since the last call to their controllers.
  void apply();
  /// Drops commands not yet applied (sim reset).
  void clear();
  /// The topics subscribed, e.g. "/tianracer/left_rear_wheel_velocity_controller/command".
  std::vector<std::string> topics() const;

 private:
  void onCommand(Controller* controller, const std_msgs::Float64::ConstPtr& msg);

  std::vector<ros::Subscriber> subscribers_;
  std::mutex mutex_;
  std::map<Controller*, double> pending_;
  struct Ignored {
    ros::WallTime last_warning;
    int since_warning = 0;
  };
  std::map<Controller*, Ignored> ignored_;  // non-finite commands, for the throttled warning
};

}  // namespace tianracer_control

#endif  // TIANRACER_CONTROL_ROS_CONTROLLER_ADAPTER_H
