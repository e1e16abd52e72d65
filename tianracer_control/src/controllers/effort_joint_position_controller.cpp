#include "tianracer_control/controllers/effort_joint_position_controller.h"

namespace tianracer_control {

double EffortJointPositionController::pidError() const {
  return joint_->continuous ? shortestAngularDistance(joint_->position, command_)
                            : command_ - joint_->position;
}

// effort_controllers/src/joint_position_controller.cpp, update(): a command from `command` has
// no velocity, so upstream calls computeCommand(error, period): the derivative is the change of
// the error (a step of the target kicks the D term for one update, as in Gazebo).
double EffortJointPositionController::pidOutput(double dt) { return pid_.computeCommand(pidError(), dt); }

}  // namespace tianracer_control
