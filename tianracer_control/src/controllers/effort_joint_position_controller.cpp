#include "tianracer_control/controllers/effort_joint_position_controller.h"

namespace tianracer_control {

double EffortJointPositionController::pidError() const {
  return joint_->continuous ? shortestAngularDistance(joint_->position, command_)
                            : command_ - joint_->position;
}

double EffortJointPositionController::pidOutput(double dt) {
  const double error_dot = 0.0 - joint_->velocity;
  return pid_.computeCommand(pidError(), error_dot, dt);
}

}  // namespace tianracer_control
