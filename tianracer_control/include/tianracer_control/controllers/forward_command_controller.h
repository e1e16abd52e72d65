// ros_controllers' forward_command_controller::ForwardCommandController: the command goes to the
// joint as it is (the hardware enforces the joint's limits, as gazebo_ros_control's
// DefaultRobotHWSim does). As in ros_controllers, one class serves three types (its
// JointEffortController, JointVelocityController and JointPositionController are typedefs of the
// template over the hardware interface):
//   effort_controllers/JointEffortController      effort; starts at 0
//   velocity_controllers/JointVelocityController  velocity target of the joint motor (limited by
//                                                 the URDF effort); starts at 0
//   position_controllers/JointPositionController  position; starts at the current position
#ifndef TIANRACER_CONTROL_CONTROLLERS_FORWARD_COMMAND_CONTROLLER_H
#define TIANRACER_CONTROL_CONTROLLERS_FORWARD_COMMAND_CONTROLLER_H

#include <memory>

#include "tianracer_control/controller.h"

namespace tianracer_control {

class ForwardCommandController : public SingleJointController {
 public:
  static constexpr const char* kEffortType = "effort_controllers/JointEffortController";
  static constexpr const char* kVelocityType = "velocity_controllers/JointVelocityController";
  static constexpr const char* kPositionType = "position_controllers/JointPositionController";

  /// Reads joint (a joint with the interface `I`).
  template <JointHandle::Interface I>
  static std::unique_ptr<Controller> create(ControllerContext& context);

  using SingleJointController::SingleJointController;
  void starting(double time) override;
  void update(double dt) override;
  bool setCommand(double value) override;
};

}  // namespace tianracer_control

#endif  // TIANRACER_CONTROL_CONTROLLERS_FORWARD_COMMAND_CONTROLLER_H
