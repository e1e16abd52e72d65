#include "tianracer_control/controllers/position_forward_controller.h"

#include <cmath>

namespace tianracer_control {

std::unique_ptr<Controller> PositionForwardController::create(ControllerContext& context) {
  JointHandle* joint = claimJoint(context, JointHandle::Interface::kPosition);
  return std::make_unique<PositionForwardController>(context.params.name(), kType, joint);
}

void PositionForwardController::starting(double) {
  command_ = clampToPositionLimits(*joint_, joint_->position);
}

bool PositionForwardController::setCommand(double value) {
  if (!std::isfinite(value)) return false;
  command_ = clampToPositionLimits(*joint_, value);
  return true;
}

void PositionForwardController::update(double) { joint_->command = command_; }

}  // namespace tianracer_control
