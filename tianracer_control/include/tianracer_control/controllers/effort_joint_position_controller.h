// effort_controllers/JointPositionController: effort = PID(position error), as ros_controllers
// computes it: error = target - position (shortest angle for continuous joints), derivative
// input = velocity error = 0 - velocity (no setpoint kick on a step). The target is clamped to
// the URDF position limits, the effort to +-effort_limit.
#ifndef TIANRACER_CONTROL_CONTROLLERS_EFFORT_JOINT_POSITION_CONTROLLER_H
#define TIANRACER_CONTROL_CONTROLLERS_EFFORT_JOINT_POSITION_CONTROLLER_H

#include <memory>
#include <string>

#include "tianracer_control/controller.h"
#include "tianracer_control/pid.h"

namespace tianracer_control {

class EffortJointPositionController : public SingleJointController {
 public:
  static constexpr const char* kType = "effort_controllers/JointPositionController";
  /// Reads joint (an effort joint) and pid/{p,i,d,i_clamp,i_clamp_min,i_clamp_max,antiwindup}.
  static std::unique_ptr<Controller> create(ControllerContext& context);

  EffortJointPositionController(std::string name, JointHandle* joint, const PidGains& gains);
  void starting(double time) override;
  void update(double dt) override;
  void reset() override { pid_.reset(); }
  bool setCommand(double value) override;
  const Pid& pid() const { return pid_; }

 private:
  Pid pid_;
};

}  // namespace tianracer_control

#endif  // TIANRACER_CONTROL_CONTROLLERS_EFFORT_JOINT_POSITION_CONTROLLER_H
