// The ROS side of a controller type: the subscriptions, publishers, tf and services upstream's
// class opens in its init(). The ROS-free class (controllers/) computes; its ROS side, made when
// the controller is loaded and dropped when it is unloaded, carries messages across:
//   - callbacks (any spinner thread) keep what arrived under the side's own mutex;
//   - apply() (the sim loop, before ControllerSet::update()) hands it to the controller;
//   - publish(t) (the sim loop, after a step) sends what the controller produced.
// The controller is only ever touched by the sim loop.
//
// A ROS side is registered beside its code, by the controller class's type name, as
// PLUGINLIB_EXPORT_CLASS registers a class:
//   TIANRACER_CONTROLLER_ROS_SIDE(DiffDriveController::kType, DiffDriveRos::create);
// A type with no ROS side has no topics (joint_state_controller: the host publishes).
#ifndef TIANRACER_CONTROL_ROS_CONTROLLER_ROS_H
#define TIANRACER_CONTROL_ROS_CONTROLLER_ROS_H

#include <memory>
#include <string>
#include <vector>

#include <ros/node_handle.h>

#include "tianracer_control/controller_set.h"

namespace tianracer_control {

/// What a ROS side is made with: controller_manager's root_nh (the robot's namespace) and
/// controller_nh (<root>/<controller name>), the controller and the set it is in (for
/// isRunning()).
struct RosSideContext {
  ros::NodeHandle root_nh;
  ros::NodeHandle controller_nh;
  Controller& controller;
  const ControllerSet& set;
};

class ControllerRosSide {
 public:
  virtual ~ControllerRosSide() = default;
  /// Messages received since the last call go to the controller.
  virtual void apply() {}
  /// Sends what the controller produced (its outbox) at sim time t.
  virtual void publish(double t) { (void)t; }
  /// Drops messages not yet applied (sim reset).
  virtual void clear() {}
  /// The topics that command the controller (the lockstep waits on them).
  virtual std::vector<std::string> commandTopics() const { return {}; }
};

using RosSideFactory = std::unique_ptr<ControllerRosSide> (*)(RosSideContext& context);

/// Registers the ROS side of controller type `type`; returns true (for the static registrar).
bool registerRosSide(const std::string& type, RosSideFactory factory);
/// The ROS side factory of `type`, null when it has none.
RosSideFactory findRosSide(const std::string& type);

#define TIANRACER_CONTROLLER_ROS_SIDE_CAT2(a, b) a##b
#define TIANRACER_CONTROLLER_ROS_SIDE_CAT(a, b) TIANRACER_CONTROLLER_ROS_SIDE_CAT2(a, b)
/// Registers a ROS side at load time of the library (one line beside the side's code).
#define TIANRACER_CONTROLLER_ROS_SIDE(type, factory)                                  \
  static const bool TIANRACER_CONTROLLER_ROS_SIDE_CAT(ros_side_registered_, __LINE__) = \
      ::tianracer_control::registerRosSide(type, factory)

/// At most one warning a second per key, counting the ones held back (a per-call-site
/// ROS_WARN_THROTTLE would let one controller's warnings hide another's).
class ThrottledWarning {
 public:
  void warn(const std::string& text);

 private:
  double last_ = -1.0;  // wall time
  int held_back_ = 0;
};

}  // namespace tianracer_control

#endif  // TIANRACER_CONTROL_ROS_CONTROLLER_ROS_H
