#include "tianracer_control/controllers/effort_joint_velocity_controller.h"

#include <cmath>

#include "tianracer_control/pid_params.h"

namespace tianracer_control {

std::unique_ptr<Controller> EffortJointVelocityController::create(ControllerContext& context) {
  JointHandle* joint = claimJoint(context, JointHandle::Interface::kEffort);
  const PidGains gains = readPidGains(context.params, context.warn);
  return std::make_unique<EffortJointVelocityController>(context.params.name(), joint, gains);
}

EffortJointVelocityController::EffortJointVelocityController(std::string name, JointHandle* joint,
                                                             const PidGains& gains)
    : SingleJointController(std::move(name), kType, joint), pid_(gains) {}

void EffortJointVelocityController::starting(double) {
  command_ = 0.0;
  pid_.reset();
}

bool EffortJointVelocityController::setCommand(double value) {
  if (!std::isfinite(value)) return false;
  command_ = clampSymmetric(value, joint_->velocity_limit);
  return true;
}

void EffortJointVelocityController::update(double dt) {
  const double error = command_ - joint_->velocity;
  joint_->command = clampSymmetric(pid_.computeCommand(error, dt), joint_->effort_limit);
}

}  // namespace tianracer_control
