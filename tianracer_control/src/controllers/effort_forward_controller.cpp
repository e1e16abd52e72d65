#include "tianracer_control/controllers/effort_forward_controller.h"

#include <cmath>

namespace tianracer_control {

std::unique_ptr<Controller> EffortForwardController::create(ControllerContext& context) {
  JointHandle* joint = claimJoint(context, JointHandle::Interface::kEffort);
  return std::make_unique<EffortForwardController>(context.params.name(), kType, joint);
}

void EffortForwardController::starting(double) { command_ = 0.0; }

bool EffortForwardController::setCommand(double value) {
  if (!std::isfinite(value)) return false;
  command_ = clampSymmetric(value, joint_->effort_limit);
  return true;
}

void EffortForwardController::update(double) { joint_->command = command_; }

}  // namespace tianracer_control
