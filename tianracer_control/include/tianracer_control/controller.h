// The base of the joint controllers (controller_interface::Controller without the ROS parts) and
// what a controller class gets when it is built. ROS-free. Each controller type lives in its own
// file under controllers/ and is registered by type name in controller_registry.cpp.
#ifndef TIANRACER_CONTROL_CONTROLLER_H
#define TIANRACER_CONTROL_CONTROLLER_H

#include <map>
#include <memory>
#include <string>
#include <vector>

#include "tianracer_control/controller_params.h"
#include "tianracer_control/joint_handle.h"

namespace urdf {
class ModelInterface;  // urdfdom's parsed robot_description (urdf_model/model.h)
}

namespace tianracer_control {

class ControllerSet;

/// Base of all controllers.
class Controller {
 public:
  Controller(std::string name, std::string type) : name_(std::move(name)), type_(std::move(type)) {}
  virtual ~Controller() = default;
  Controller(const Controller&) = delete;
  Controller& operator=(const Controller&) = delete;

  const std::string& name() const { return name_; }
  const std::string& type() const { return type_; }

  /// The joint this controller writes, nullptr if none or several (see claimedJoints()).
  virtual const JointHandle* joint() const { return nullptr; }
  /// Every joint this controller writes, each through its handle's interface (what
  /// hardware_interface's ClaimedResources list). Default: joint(), if any.
  virtual std::vector<const JointHandle*> claimedJoints() const {
    if (const JointHandle* j = joint()) return {j};
    return {};
  }
  /// The sim time of the update running (or of the last starting()); ControllerSet sets it,
  /// as controller_manager passes `time` to update() and starting().
  double now() const { return now_; }

  /// Called when the controller starts (load, sim reset). Position controllers take the current
  /// position as their target so that nothing jumps; velocity controllers start at 0.
  virtual void starting(double time) { (void)time; }
  /// Computes and writes joint()->command. dt in seconds (the control period).
  virtual void update(double dt) = 0;
  /// Forgets dynamic state (PID integrator and history); ControllerSet::reset() then restarts.
  virtual void reset() {}

  /// Controllers with a command topic (/<ns>/<name>/command).
  virtual bool hasCommand() const { return false; }
  /// Sets the target. Non-finite values are rejected: returns false, the previous command stays.
  /// Finite values are clamped to the joint's limits.
  virtual bool setCommand(double value) {
    (void)value;
    return false;
  }
  virtual double command() const { return 0.0; }

 private:
  friend class ControllerSet;
  std::string name_;
  std::string type_;
  double now_ = 0.0;
};

/// What a controller class is built from (controller_interface's init(hw, root_nh,
/// controller_nh)): its parameters, the joints that have a transmission by name, where warnings
/// go, and the robot's parsed robot_description (null when the host has none; what upstream's
/// controllers read from the parameter server, e.g. diff_drive_controller's wheel radius).
struct ControllerContext {
  ControllerParams& params;
  std::map<std::string, JointHandle*>& joints;
  const WarningSink& warn;
  const urdf::ModelInterface* robot_description = nullptr;
};

/// Finds `joint` among context.joints for controller type `type`. Throws ControllerError,
/// naming the controller, for a joint without a transmission, or a transmission whose
/// interface is not `needs` (naming both interfaces).
JointHandle* findJoint(ControllerContext& context, const std::string& joint,
                       JointHandle::Interface needs);

/// Shared code of the controllers that command one joint.
class SingleJointController : public Controller {
 public:
  SingleJointController(std::string name, std::string type, JointHandle* joint)
      : Controller(std::move(name), std::move(type)), joint_(joint) {}
  const JointHandle* joint() const override { return joint_; }
  bool hasCommand() const override { return true; }
  double command() const override { return command_; }

  /// Reads `joint` and finds it among context.joints. Throws ControllerError, naming the
  /// controller, for a missing joint, a joint without a transmission, or a transmission whose
  /// interface is not `needs` (naming both interfaces).
  static JointHandle* claimJoint(ControllerContext& context, JointHandle::Interface needs);

 protected:
  JointHandle* joint_;
  double command_ = 0.0;
};

/// angles::shortest_angular_distance: (to - from) wrapped into [-pi, pi).
double shortestAngularDistance(double from, double to);

/// x clamped to the joint's position limits, if it has any: the enforceJointLimits of
/// effort_controllers' JointPositionController and JointGroupPositionController and of
/// velocity_controllers' JointPositionController, the only upstream controllers that clamp.
double clampToPositionLimits(const JointHandle& joint, double x);

}  // namespace tianracer_control

#endif  // TIANRACER_CONTROL_CONTROLLER_H
