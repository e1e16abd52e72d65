#include "tianracer_control/controllers/forward_command_controller.h"

#include <cmath>

namespace tianracer_control {

template <JointHandle::Interface I>
std::unique_ptr<Controller> ForwardCommandController::create(ControllerContext& context) {
  JointHandle* joint = claimJoint(context, I);
  return std::make_unique<ForwardCommandController>(context.params.name(), context.params.type(),
                                                    joint);
}

template std::unique_ptr<Controller> ForwardCommandController::create<
    JointHandle::Interface::kEffort>(ControllerContext&);
template std::unique_ptr<Controller> ForwardCommandController::create<
    JointHandle::Interface::kVelocity>(ControllerContext&);
template std::unique_ptr<Controller> ForwardCommandController::create<
    JointHandle::Interface::kPosition>(ControllerContext&);

double ForwardCommandController::clamp(double value) const {
  switch (joint_->interface) {
    case JointHandle::Interface::kEffort:
      return clampSymmetric(value, joint_->effort_limit);
    case JointHandle::Interface::kVelocity:
      return clampSymmetric(value, joint_->velocity_limit);
    case JointHandle::Interface::kPosition:
      return clampToPositionLimits(*joint_, value);
  }
  return value;
}

void ForwardCommandController::starting(double) {
  command_ = joint_->interface == JointHandle::Interface::kPosition ? clamp(joint_->position) : 0.0;
}

bool ForwardCommandController::setCommand(double value) {
  if (!std::isfinite(value)) return false;
  command_ = clamp(value);
  return true;
}

void ForwardCommandController::update(double) { joint_->command = command_; }

}  // namespace tianracer_control
