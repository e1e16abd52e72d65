// velocity_controllers/JointVelocityController: the command is the velocity target of the joint
// motor (the simulator limits the motor by the URDF effort), clamped to +-velocity_limit.
#ifndef TIANRACER_CONTROL_CONTROLLERS_VELOCITY_FORWARD_CONTROLLER_H
#define TIANRACER_CONTROL_CONTROLLERS_VELOCITY_FORWARD_CONTROLLER_H

#include <memory>

#include "tianracer_control/controller.h"

namespace tianracer_control {

class VelocityForwardController : public SingleJointController {
 public:
  static constexpr const char* kType = "velocity_controllers/JointVelocityController";
  /// Reads joint (a joint with the velocity interface).
  static std::unique_ptr<Controller> create(ControllerContext& context);

  using SingleJointController::SingleJointController;
  void starting(double time) override;
  void update(double dt) override;
  bool setCommand(double value) override;
};

}  // namespace tianracer_control

#endif  // TIANRACER_CONTROL_CONTROLLERS_VELOCITY_FORWARD_CONTROLLER_H
