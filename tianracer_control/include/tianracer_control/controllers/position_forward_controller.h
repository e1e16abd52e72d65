// position_controllers/JointPositionController: the command is the joint position, clamped to
// the URDF limits; starts at the current position.
#ifndef TIANRACER_CONTROL_CONTROLLERS_POSITION_FORWARD_CONTROLLER_H
#define TIANRACER_CONTROL_CONTROLLERS_POSITION_FORWARD_CONTROLLER_H

#include <memory>

#include "tianracer_control/controller.h"

namespace tianracer_control {

class PositionForwardController : public SingleJointController {
 public:
  static constexpr const char* kType = "position_controllers/JointPositionController";
  /// Reads joint (a joint with the position interface).
  static std::unique_ptr<Controller> create(ControllerContext& context);

  using SingleJointController::SingleJointController;
  void starting(double time) override;
  void update(double dt) override;
  bool setCommand(double value) override;
};

}  // namespace tianracer_control

#endif  // TIANRACER_CONTROL_CONTROLLERS_POSITION_FORWARD_CONTROLLER_H
