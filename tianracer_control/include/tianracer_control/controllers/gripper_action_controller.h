// gripper_action_controller (ros_controllers noetic-devel, gripper_action_controller_impl.h:
// init, starting, update, goalCB, cancelCB, setHoldPosition, checkForSuccess;
// hardware_interface_adapter.h for the commands):
//   position_controllers/GripperActionController  command = the goal position
//   effort_controllers/GripperActionController    command = PID(position error, -velocity)
//                                                 clamped to +-max_effort; gains under
//                                                 gains/<joint>
// ROS-free: goals are numbered and their outcomes queued for the ROS side (the
// control_msgs/GripperCommand action server, ros/gripper_action_ros.cpp).
#ifndef TIANRACER_CONTROL_CONTROLLERS_GRIPPER_ACTION_CONTROLLER_H
#define TIANRACER_CONTROL_CONTROLLERS_GRIPPER_ACTION_CONTROLLER_H

#include <cstdint>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "tianracer_control/controller.h"
#include "tianracer_control/pid.h"

namespace tianracer_control {

class GripperActionController : public SingleJointController {
 public:
  static constexpr const char* kPositionType = "position_controllers/GripperActionController";
  static constexpr const char* kEffortType = "effort_controllers/GripperActionController";
  using GoalId = std::uint64_t;

  struct Options {
    double goal_tolerance = 0.01;             // |position error| below this: reached
    double max_effort = 0.0;                  // default max_effort (hold, start)
    double stall_velocity_threshold = 0.001;  // |velocity| above this: moving
    double stall_timeout = 1.0;               // [s] not moving this long: stalled
    double action_monitor_rate = 20.0;        // [Hz]
  };

  /// Reads `joint`, the options and, for the effort form, gains/<joint>. Throws
  /// ControllerError (upstream's "Could not find joint name on param server", a key of the
  /// wrong kind, a non-finite value or a rate <= 0).
  template <JointHandle::Interface I>
  static std::unique_ptr<Controller> create(ControllerContext& context);

  /// pid: for the effort form only.
  GripperActionController(std::string name, std::string type, JointHandle* joint,
                          const Options& options, std::optional<Pid> pid);

  const Options& options() const { return options_; }
  void starting(double time) override;
  void update(double dt) override;
  void reset() override;
  bool hasCommand() const override { return false; }  // commanded by its action only
  double command() const override { return target_; }
  double maxEffort() const { return max_effort_; }

  /// GripperCommandResult and what became of the goal.
  struct GoalEvent {
    enum class Kind { kSucceeded, kAborted, kCanceled };
    GoalId goal = 0;
    Kind kind = Kind::kSucceeded;
    double position = 0.0;
    double effort = 0.0;
    bool stalled = false;
    bool reached_goal = false;
  };
  std::vector<GoalEvent> takeGoalEvents();

  /// goalCB: "" = accepted (the active goal is canceled first), else why it is rejected.
  std::string startGoal(GoalId goal, double position, double max_effort);
  /// cancelCB: when `goal` is the active one, hold the current position at the default
  /// max_effort and report it canceled; true then.
  bool cancelGoal(GoalId goal);
  GoalId activeGoal() const { return active_goal_; }
  bool running() const { return running_; }

 private:
  void checkForSuccess(double time, double error_position);
  void finish(GoalEvent::Kind kind, bool stalled, bool reached);

  Options options_;
  std::optional<Pid> pid_;
  double target_ = 0.0;
  double max_effort_ = 0.0;
  double computed_command_ = 0.0;  // the adapter's last result (the effort reported)
  double last_movement_time_ = 0.0;
  bool running_ = false;
  GoalId active_goal_ = 0;
  std::vector<GoalEvent> events_;
};

}  // namespace tianracer_control

#endif  // TIANRACER_CONTROL_CONTROLLERS_GRIPPER_ACTION_CONTROLLER_H
