// effort_controllers/JointVelocityController: effort = PID(target velocity - velocity), the
// derivative taken from successive errors. Neither the target nor the effort is clamped here, as
// upstream's (effort_controllers/src/joint_velocity_controller.cpp); the hardware enforces the
// joint's limits (gazebo_ros_control's DefaultRobotHWSim, tianracer_sim's RobotHwSim).
#ifndef TIANRACER_CONTROL_CONTROLLERS_EFFORT_JOINT_VELOCITY_CONTROLLER_H
#define TIANRACER_CONTROL_CONTROLLERS_EFFORT_JOINT_VELOCITY_CONTROLLER_H

#include "tianracer_control/controllers/effort_pid_controller.h"

namespace tianracer_control {

class EffortJointVelocityController
    : public EffortPidController<EffortJointVelocityController> {
 public:
  static constexpr const char* kType = "effort_controllers/JointVelocityController";
  using EffortPidController::EffortPidController;

  /// Starts at rest.
  double startTarget() const { return 0.0; }
  double clampTarget(double target) const { return target; }
  double pidOutput(double dt) { return pid_.computeCommand(pidError(), dt); }
  double pidError() const { return command_ - joint_->velocity; }
  double processValue() const { return joint_->velocity; }
  double processValueDot() const { return 0.0; }
};

}  // namespace tianracer_control

#endif  // TIANRACER_CONTROL_CONTROLLERS_EFFORT_JOINT_VELOCITY_CONTROLLER_H
