// ros_controllers-style joint controllers run inside the simulator's step loop. ROS-free: the ROS
// adapter (tianracer_control/ros/) turns the parameter server into ControllerSpecs and command
// topics into setCommand(); all validation lives here so that it is unit tested.
#ifndef TIANRACER_CONTROL_JOINT_CONTROLLERS_H
#define TIANRACER_CONTROL_JOINT_CONTROLLERS_H

#include <functional>
#include <map>
#include <memory>
#include <optional>
#include <stdexcept>
#include <string>
#include <vector>

#include "tianracer_control/diagnostic.h"  // InputError, WarningSink
#include "tianracer_control/joint_handle.h"
#include "tianracer_control/pid.h"

namespace tianracer_control {

/// A configuration error; the message starts with "controller '<name>': ".
using ControllerError = InputError;

/// The pid/ keys as written in the YAML; unset = absent. Converted and checked by toPidGains().
struct PidParams {
  std::optional<double> p, i, d, i_clamp, i_clamp_min, i_clamp_max;
  std::optional<bool> antiwindup;

  PidParams() = default;
  /// Lets code that already has gains write `spec.pid = gains;`.
  PidParams(const PidGains& g)  // NOLINT(google-explicit-constructor)
      : p(g.p), i(g.i), d(g.d), i_clamp_min(g.i_clamp_min), i_clamp_max(g.i_clamp_max),
        antiwindup(g.antiwindup) {}
};

/// One entry of a ros_control YAML, e.g.
///   left_steering_hinge_position_controller:
///     type: effort_controllers/JointPositionController
///     joint: left_steering_hinge_joint
///     pid: {p: 1.0, i: 0.0, d: 0.05}
struct ControllerSpec {
  std::string name;
  std::string type;
  std::string joint;
  std::optional<PidParams> pid;
  std::optional<double> publish_rate;  // joint_state_controller (Hz)
  /// Every key found under the controller ("type", "joint", "pid", "pid/p", ...), if the reader
  /// knows them: keys no controller of this type reads are reported as warnings.
  std::vector<std::string> keys;
  int line = 0;  // source line where known (0 = unknown)
};

/// pid/{p,i,d,i_clamp,i_clamp_min,i_clamp_max,antiwindup} -> gains, with control_toolbox's rules:
/// p is required; i, d default to 0; i_clamp_min/max override i_clamp (min = -|i_clamp|,
/// max = |i_clamp|); all clamps default to 0, which disables the integral term (warned when i != 0).
/// Throws ControllerError (naming `controller`) for a missing p, non-finite values or min > max.
PidGains toPidGains(const std::string& controller, const PidParams& params,
                    const WarningSink& warn = WarningSink());

/// Base of all controllers (controller_interface::Controller without the ROS parts).
class Controller {
 public:
  Controller(std::string name, std::string type) : name_(std::move(name)), type_(std::move(type)) {}
  virtual ~Controller() = default;
  Controller(const Controller&) = delete;
  Controller& operator=(const Controller&) = delete;

  const std::string& name() const { return name_; }
  const std::string& type() const { return type_; }

  /// The joint this controller writes, nullptr if none (joint_state_controller).
  virtual const JointHandle* joint() const { return nullptr; }

  /// Called when the controller starts (load, sim reset). Position controllers take the current
  /// position as their target so that nothing jumps; velocity controllers start at 0.
  virtual void starting(double time) { (void)time; }
  /// Computes and writes joint()->command. dt in seconds (the control period).
  virtual void update(double dt) = 0;
  /// Forgets dynamic state (PID integrator and history); ControllerSet::reset() then restarts.
  virtual void reset() {}

  /// Controllers with a command topic (/<ns>/<name>/command).
  virtual bool hasCommand() const { return false; }
  /// Sets the target. Non-finite values are rejected: returns false, the previous command stays.
  /// Finite values are clamped to the joint's limits.
  virtual bool setCommand(double value) {
    (void)value;
    return false;
  }
  virtual double command() const { return 0.0; }

 private:
  std::string name_;
  std::string type_;
};

/// joint_state_controller/JointStateController: publishes nothing itself; tells the host when
/// to publish all joint states, at publish_rate in sim time.
class JointStateController : public Controller {
 public:
  JointStateController(std::string name, double publish_rate);
  void starting(double time) override;
  void update(double) override {}
  /// True when a message is due at sim time t (at most once per call). The first call after
  /// starting() is due; then every 1/publish_rate. A jump back in time (sim reset) restarts the
  /// schedule; a long gap does not cause a burst.
  bool due(double t);
  double publishRate() const { return rate_; }

 private:
  double rate_;
  double period_;
  double next_ = 0.0;
  bool started_ = false;
};

/// Shared code of the controllers that command one joint.
class SingleJointController : public Controller {
 public:
  SingleJointController(std::string name, std::string type, JointHandle* joint)
      : Controller(std::move(name), std::move(type)), joint_(joint) {}
  const JointHandle* joint() const override { return joint_; }
  bool hasCommand() const override { return true; }
  double command() const override { return command_; }

 protected:
  JointHandle* joint_;
  double command_ = 0.0;
};

/// effort_controllers/JointPositionController: effort = PID(position error), as ros_controllers
/// computes it: error = target - position (shortest angle for continuous joints), derivative
/// input = velocity error = 0 - velocity (no setpoint kick on a step). The target is clamped to
/// the URDF position limits, the effort to +-effort_limit.
class EffortJointPositionController : public SingleJointController {
 public:
  EffortJointPositionController(std::string name, JointHandle* joint, const PidGains& gains);
  void starting(double time) override;
  void update(double dt) override;
  void reset() override { pid_.reset(); }
  bool setCommand(double value) override;
  const Pid& pid() const { return pid_; }

 private:
  Pid pid_;
};

/// effort_controllers/JointVelocityController: effort = PID(target velocity - velocity), the
/// derivative taken from successive errors. Target clamped to +-velocity_limit, effort to
/// +-effort_limit.
class EffortJointVelocityController : public SingleJointController {
 public:
  EffortJointVelocityController(std::string name, JointHandle* joint, const PidGains& gains);
  void starting(double time) override;
  void update(double dt) override;
  void reset() override { pid_.reset(); }
  bool setCommand(double value) override;
  const Pid& pid() const { return pid_; }

 private:
  Pid pid_;
};

/// effort_controllers/JointEffortController: the command is the effort, clamped to +-effort_limit.
class EffortForwardController : public SingleJointController {
 public:
  using SingleJointController::SingleJointController;
  void starting(double time) override;
  void update(double dt) override;
  bool setCommand(double value) override;
};

/// velocity_controllers/JointVelocityController: the command is the velocity target of the joint
/// motor (the simulator limits the motor by the URDF effort), clamped to +-velocity_limit.
class VelocityForwardController : public SingleJointController {
 public:
  using SingleJointController::SingleJointController;
  void starting(double time) override;
  void update(double dt) override;
  bool setCommand(double value) override;
};

/// position_controllers/JointPositionController: the command is the joint position, clamped to
/// the URDF limits; starts at the current position.
class PositionForwardController : public SingleJointController {
 public:
  using SingleJointController::SingleJointController;
  void starting(double time) override;
  void update(double dt) override;
  bool setCommand(double value) override;
};

/// The controller types makeController() knows, e.g. "effort_controllers/JointPositionController".
const std::vector<std::string>& knownControllerTypes();

/// Builds a controller from its spec. `joints` holds the joints that have a transmission, by name.
/// Throws ControllerError, naming the controller, for an unknown type, a missing joint, a joint
/// not in `joints`, an interface mismatch (naming both interfaces), missing or bad pid gains, a
/// missing or non-positive publish_rate. Unknown keys go to `warn`.
std::unique_ptr<Controller> makeController(const ControllerSpec& spec,
                                           std::map<std::string, JointHandle*>& joints,
                                           const WarningSink& warn = WarningSink());

/// The running controllers of one robot (controller_manager without ROS).
class ControllerSet {
 public:
  /// Adds and starts a controller at `time`. Throws ControllerError for a duplicate name or a
  /// joint already written by another controller (ros_control's resource conflict).
  Controller& add(std::unique_ptr<Controller> controller, double time = 0.0);
  /// makeController() + add().
  Controller& load(const ControllerSpec& spec, std::map<std::string, JointHandle*>& joints,
                   double time = 0.0, const WarningSink& warn = WarningSink());

  /// Updates every controller in the order they were added (call between read and write).
  void update(double dt);
  /// Sim reset: clears every PID and restarts every controller at `time`.
  void reset(double time = 0.0);

  Controller* find(const std::string& name);
  const Controller* find(const std::string& name) const;
  const std::vector<std::unique_ptr<Controller>>& controllers() const { return controllers_; }
  std::size_t size() const { return controllers_.size(); }
  bool empty() const { return controllers_.empty(); }

 private:
  std::vector<std::unique_ptr<Controller>> controllers_;
};

/// angles::shortest_angular_distance: (to - from) wrapped into [-pi, pi).
double shortestAngularDistance(double from, double to);

}  // namespace tianracer_control

#endif  // TIANRACER_CONTROL_JOINT_CONTROLLERS_H
