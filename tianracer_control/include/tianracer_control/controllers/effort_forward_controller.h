// effort_controllers/JointEffortController: the command is the effort, clamped to +-effort_limit.
#ifndef TIANRACER_CONTROL_CONTROLLERS_EFFORT_FORWARD_CONTROLLER_H
#define TIANRACER_CONTROL_CONTROLLERS_EFFORT_FORWARD_CONTROLLER_H

#include <memory>

#include "tianracer_control/controller.h"

namespace tianracer_control {

class EffortForwardController : public SingleJointController {
 public:
  static constexpr const char* kType = "effort_controllers/JointEffortController";
  /// Reads joint (a joint with the effort interface).
  static std::unique_ptr<Controller> create(ControllerContext& context);

  using SingleJointController::SingleJointController;
  void starting(double time) override;
  void update(double dt) override;
  bool setCommand(double value) override;
};

}  // namespace tianracer_control

#endif  // TIANRACER_CONTROL_CONTROLLERS_EFFORT_FORWARD_CONTROLLER_H
