// effort_controllers/JointPositionController: effort = PID(position error), as ros_controllers
// computes it: error = target - position (shortest angle for continuous joints), derivative
// input = velocity error = 0 - velocity (no setpoint kick on a step). The target is clamped to
// the URDF position limits, the effort to +-effort_limit.
#ifndef TIANRACER_CONTROL_CONTROLLERS_EFFORT_JOINT_POSITION_CONTROLLER_H
#define TIANRACER_CONTROL_CONTROLLERS_EFFORT_JOINT_POSITION_CONTROLLER_H

#include "tianracer_control/controllers/effort_pid_controller.h"

namespace tianracer_control {

class EffortJointPositionController
    : public EffortPidController<EffortJointPositionController> {
 public:
  static constexpr const char* kType = "effort_controllers/JointPositionController";
  using EffortPidController::EffortPidController;

  /// The current position, clamped to the limits.
  double startTarget() const { return clampTarget(joint_->position); }
  double clampTarget(double target) const { return clampToPositionLimits(*joint_, target); }
  double pidOutput(double dt);
  double pidError() const;
  double processValue() const { return joint_->position; }
  double processValueDot() const { return joint_->velocity; }
};

}  // namespace tianracer_control

#endif  // TIANRACER_CONTROL_CONTROLLERS_EFFORT_JOINT_POSITION_CONTROLLER_H
