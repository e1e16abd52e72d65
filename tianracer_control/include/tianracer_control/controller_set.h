// A robot's controllers (controller_manager without ROS): loaded, started, stopped and unloaded
// by name, with controller_manager's rules and error texts (ros_control noetic-devel,
// controller_manager/src/controller_manager.cpp; the resource check of
// hardware_interface/robot_hw.h). ROS-free.
#ifndef TIANRACER_CONTROL_CONTROLLER_SET_H
#define TIANRACER_CONTROL_CONTROLLER_SET_H

#include <map>
#include <memory>
#include <string>
#include <vector>

#include "tianracer_control/controller.h"
#include "tianracer_control/controller_registry.h"

namespace tianracer_control {

/// A loaded controller's state, as list_controllers reports it: a controller is initialized
/// after loading, running once started, stopped once stopped.
enum class ControllerState { kInitialized, kRunning, kStopped };
/// "initialized", "running", "stopped"
const char* toString(ControllerState state);

/// switch_controller's strictness (controller_manager_msgs/SwitchController's constants).
enum class Strictness { kBestEffort = 1, kStrict = 2 };

/// What a controller claims (controller_manager_msgs/HardwareInterfaceResources), e.g.
/// {"hardware_interface::EffortJointInterface", {"left_steering_hinge_joint"}}.
struct ClaimedResources {
  std::string hardware_interface;
  std::vector<std::string> resources;
};

class ControllerSet {
 public:
  // --- Start-up: a controller loaded and started at once --------------------------------
  /// Adds and starts a controller at `time`. Throws ControllerError for a duplicate name or a
  /// joint already written by another controller (a configuration error at start-up).
  Controller& add(std::unique_ptr<Controller> controller, double time = 0.0);
  /// builtinControllers().create() + add().
  Controller& load(const ControllerSpec& spec, std::map<std::string, JointHandle*>& joints,
                   double time = 0.0, const WarningSink& warn = WarningSink());

  // --- controller_manager: load_controller, unload_controller, switch_controller ---------
  // Each throws ControllerError whose message is controller_manager's error text (one line per
  // error it logs); nothing changes then.
  /// Builds the controller and keeps it initialized (not running). Errors: "A controller named
  /// 'x' was already loaded inside the controller manager"; for a type the registry does not
  /// have, "Could not load controller 'x' because controller type 'T' does not exist." and
  /// "Use 'rosservice call controller_manager/list_controller_types' to get the available
  /// types"; for a class that refuses its parameters, the class's message and "Initializing
  /// controller 'x' failed". Two loaded controllers may claim one joint; only one may run.
  Controller& loadController(const ControllerSpec& spec,
                             std::map<std::string, JointHandle*>& joints,
                             const WarningSink& warn = WarningSink(),
                             const ControllerRegistry& registry = builtinControllers());
  /// Errors: "Could not unload controller with name 'x' because no controller with this name
  /// exists"; "... because it is still running".
  void unloadController(const std::string& name);
  /// Stops `stop`, then starts `start` (starting(time)), all or nothing. kStrict fails on a
  /// name not loaded ("Could not stop|start controller with name 'x' because no controller
  /// with this name exists"), a stop of a controller not running ("Could not stop controller
  /// 'x' since it is not running") and a start of one running ("Controller 'x' is already
  /// running"); kBestEffort skips those. Both fail on a controller in both lists and on two
  /// running controllers claiming one joint ("Resource conflict on [j].  Controllers = [a, b,
  /// ]" and "Could not switch controllers, due to resource conflict").
  void switchControllers(const std::vector<std::string>& start,
                         const std::vector<std::string>& stop, Strictness strictness,
                         double time);

  /// Updates the running controllers in the order they were loaded (between read and write), at
  /// sim time `time` (Controller::now()).
  void update(double dt, double time);
  /// Same, the time advanced by dt from the last update or start.
  void update(double dt) { update(dt, clock_ + dt); }
  /// The parsed robot_description the controllers are built with (ControllerContext); null by
  /// default. It must outlive the set.
  void setRobotDescription(const urdf::ModelInterface* description) { description_ = description; }
  /// Sim reset: clears every PID and restarts every running controller at `time`.
  void reset(double time = 0.0);

  Controller* find(const std::string& name);
  const Controller* find(const std::string& name) const;
  /// Every loaded controller, in load order, running or not.
  const std::vector<std::unique_ptr<Controller>>& controllers() const { return controllers_; }
  ControllerState state(const Controller& controller) const;
  bool isRunning(const Controller& controller) const {
    return state(controller) == ControllerState::kRunning;
  }
  /// JointStateController: the JointStateInterface, no resource; the others: their claimed
  /// joints, grouped by interface (first appearance order).
  static std::vector<ClaimedResources> claimedResources(const Controller& controller);
  std::size_t size() const { return controllers_.size(); }
  bool empty() const { return controllers_.empty(); }

 private:
  std::size_t indexOf(const Controller& controller) const;
  void startController(Controller& controller, double time);

  std::vector<std::unique_ptr<Controller>> controllers_;
  std::vector<ControllerState> states_;  // one per controller
  const urdf::ModelInterface* description_ = nullptr;
  double clock_ = 0.0;  // time of the last update or start
};

}  // namespace tianracer_control

#endif  // TIANRACER_CONTROL_CONTROLLER_SET_H
