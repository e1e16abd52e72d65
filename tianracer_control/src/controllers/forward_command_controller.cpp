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

void ForwardCommandController::starting(double) {
  command_ = joint_->interface == JointHandle::Interface::kPosition ? joint_->position : 0.0;
}

bool ForwardCommandController::setCommand(double value) {
  if (!std::isfinite(value)) return false;
  command_ = value;
  return true;
}

void ForwardCommandController::update(double) { joint_->command = command_; }

}  // namespace tianracer_control
