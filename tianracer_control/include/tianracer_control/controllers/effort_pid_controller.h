// What effort_controllers' JointPositionController and JointVelocityController share: an effort
// joint driven by a control_toolbox PID, the target clamped to the joint's limits and the effort
// to +-effort_limit. ros_controllers keeps them as two classes, registered as two types; so does
// this, each (Derived, CRTP) giving only its target rules and its PID step:
//   double startTarget() const;           the target on starting()
//   double clampTarget(double) const;     a commanded target, clamped
//   double pidOutput(double dt);          the PID's effort for the current target, unclamped
//   double pidError() const;              the error it was given (the `state` topic's)
//   double processValue() const;          the controlled value, and its derivative
//   double processValueDot() const;       (upstream leaves it 0 for a velocity)
#ifndef TIANRACER_CONTROL_CONTROLLERS_EFFORT_PID_CONTROLLER_H
#define TIANRACER_CONTROL_CONTROLLERS_EFFORT_PID_CONTROLLER_H

#include <cmath>
#include <memory>
#include <string>
#include <utility>

#include "tianracer_control/controller.h"
#include "tianracer_control/controllers/pid_state.h"
#include "tianracer_control/pid.h"
#include "tianracer_control/pid_params.h"

namespace tianracer_control {

template <class Derived>
class EffortPidController : public SingleJointController, public PidStateSource {
 public:
  /// Reads joint (an effort joint) and pid/{p,i,d,i_clamp,i_clamp_min,i_clamp_max,antiwindup}.
  static std::unique_ptr<Controller> create(ControllerContext& context) {
    JointHandle* joint = claimJoint(context, JointHandle::Interface::kEffort);
    const PidGains gains = readPidGains(context.params, context.warn);
    return std::make_unique<Derived>(context.params.name(), joint, gains);
  }

  EffortPidController(std::string name, JointHandle* joint, const PidGains& gains)
      : SingleJointController(std::move(name), Derived::kType, joint), pid_(gains) {}

  void starting(double) override {
    command_ = derived().startTarget();
    pid_.reset();
  }
  void update(double dt) override {
    // Upstream sets the PID's output as it is; the hardware saturates it to the effort limit.
    const double effort = derived().pidOutput(dt);
    joint_->command = effort;
    recordPidState(command_, derived().processValue(), derived().processValueDot(),
                   derived().pidError(), dt, effort, pid_.gains());
  }
  void reset() override { pid_.reset(); }
  bool setCommand(double value) override {
    if (!std::isfinite(value)) return false;
    command_ = derived().clampTarget(value);
    return true;
  }
  const Pid& pid() const { return pid_; }

 protected:
  Pid pid_;

 private:
  Derived& derived() { return static_cast<Derived&>(*this); }
};

}  // namespace tianracer_control

#endif  // TIANRACER_CONTROL_CONTROLLERS_EFFORT_PID_CONTROLLER_H
