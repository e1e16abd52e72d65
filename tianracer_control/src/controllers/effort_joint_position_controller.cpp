#include "tianracer_control/controllers/effort_joint_position_controller.h"

#include <cmath>

#include "tianracer_control/pid_params.h"

namespace tianracer_control {

std::unique_ptr<Controller> EffortJointPositionController::create(ControllerContext& context) {
  JointHandle* joint = claimJoint(context, JointHandle::Interface::kEffort);
  const PidGains gains = readPidGains(context.params, context.warn);
  return std::make_unique<EffortJointPositionController>(context.params.name(), joint, gains);
}

EffortJointPositionController::EffortJointPositionController(std::string name, JointHandle* joint,
                                                             const PidGains& gains)
    : SingleJointController(std::move(name), kType, joint), pid_(gains) {}

void EffortJointPositionController::starting(double) {
  command_ = clampToPositionLimits(*joint_, joint_->position);
  pid_.reset();
}

bool EffortJointPositionController::setCommand(double value) {
  if (!std::isfinite(value)) return false;
  command_ = clampToPositionLimits(*joint_, value);
  return true;
}

void EffortJointPositionController::update(double dt) {
  const double error = joint_->continuous ? shortestAngularDistance(joint_->position, command_)
                                          : command_ - joint_->position;
  const double error_dot = 0.0 - joint_->velocity;
  joint_->command = clampSymmetric(pid_.computeCommand(error, error_dot, dt), joint_->effort_limit);
}

}  // namespace tianracer_control
