#include "tianracer_control/controllers/velocity_forward_controller.h"

#include <cmath>

namespace tianracer_control {

std::unique_ptr<Controller> VelocityForwardController::create(ControllerContext& context) {
  JointHandle* joint = claimJoint(context, JointHandle::Interface::kVelocity);
  return std::make_unique<VelocityForwardController>(context.params.name(), kType, joint);
}

void VelocityForwardController::starting(double) { command_ = 0.0; }

bool VelocityForwardController::setCommand(double value) {
  if (!std::isfinite(value)) return false;
  command_ = clampSymmetric(value, joint_->velocity_limit);
  return true;
}

void VelocityForwardController::update(double) { joint_->command = command_; }

}  // namespace tianracer_control
