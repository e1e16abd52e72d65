// joint_trajectory_controller's controller class (ros_controllers noetic-devel,
// joint_trajectory_controller_impl.h: init, starting, update, updateTrajectoryCommand, goalCB,
// cancelCB, preemptActiveGoal, queryStateService, publishState, updateStates;
// hardware_interface_adapter.h for the commands), over the ROS-free core in trajectory/:
//   position_controllers/JointTrajectoryController  command = desired position
//   velocity_controllers/JointTrajectoryController  command = velocity_ff * desired velocity
//   effort_controllers/JointTrajectoryController      + PID(position error, velocity error),
//                                                     gains under gains/<joint>
// ROS-free: goals are numbered (GoalId) and their outcomes queued for the ROS side, which owns
// the actionlib goal handles (ros/joint_trajectory_ros.cpp).
#ifndef TIANRACER_CONTROL_CONTROLLERS_JOINT_TRAJECTORY_CONTROLLER_H
#define TIANRACER_CONTROL_CONTROLLERS_JOINT_TRAJECTORY_CONTROLLER_H

#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include "tianracer_control/controller.h"
#include "tianracer_control/pid.h"
#include "tianracer_control/trajectory/controller_options.h"
#include "tianracer_control/trajectory/joint_trajectory.h"

namespace tianracer_control {

class JointTrajectoryController : public Controller {
 public:
  static constexpr const char* kPositionType = "position_controllers/JointTrajectoryController";
  static constexpr const char* kVelocityType = "velocity_controllers/JointTrajectoryController";
  static constexpr const char* kEffortType = "effort_controllers/JointTrajectoryController";

  /// Reads `joints` (each a joint with interface I), the options (controller_options.h) and,
  /// for velocity and effort, gains/<joint> (a PID each, required) and velocity_ff/<joint>
  /// (default 0). Throws ControllerError with upstream's message.
  template <JointHandle::Interface I>
  static std::unique_ptr<Controller> create(ControllerContext& context);

  /// pids and velocity_ff: one per joint for velocity and effort, empty for position.
  JointTrajectoryController(std::string name, std::string type, std::vector<JointHandle*> joints,
                            trajectory::TrajectoryControllerOptions options, std::vector<Pid> pids,
                            std::vector<double> velocity_ff);

  std::vector<const JointHandle*> claimedJoints() const override;
  const std::vector<std::string>& jointNames() const { return joint_names_; }
  const trajectory::TrajectoryControllerOptions& options() const { return options_; }

  /// starting(): uptime 0, desired = the joints' state, hold; an active goal is preempted
  /// (upstream's stopping()).
  void starting(double time) override;
  void update(double dt) override;
  void reset() override;

  /// What became of a goal (for the action server): succeeded, aborted (error_code -4/-5 and
  /// error_string) or canceled (preempted by a newer goal or command, or canceled).
  struct GoalEvent {
    enum class Kind { kSucceeded, kAborted, kCanceled };
    trajectory::GoalId goal = 0;
    Kind kind = Kind::kSucceeded;
    int error_code = 0;
    std::string error_string;
  };
  /// The events since the last call, in order.
  std::vector<GoalEvent> takeGoalEvents();

  /// What a command or goal got: "" = taken; else upstream's reason (nothing changes).
  struct CommandResult {
    std::string error;
    int error_code = 0;  // for goals: FollowJointTrajectoryResult's INVALID_GOAL (-1) / JOINTS (-2)
    std::vector<std::string> warnings;  // points dropped from the past, ...
    bool ok() const { return error.empty(); }
  };
  /// The `command` topic (trajectoryCommandCB): a trajectory replacing the current one from its
  /// start; no points = hold. Taken: the active goal is canceled.
  CommandResult command(const trajectory::JointTrajectoryCommand& command);
  /// An action goal (goalCB): rejected (INVALID_JOINTS, INVALID_GOAL with the reason) or
  /// accepted, preempting the active goal. `goal` must be non-zero and new.
  CommandResult startGoal(trajectory::GoalId goal, const trajectory::JointTrajectoryCommand& command,
                          const trajectory::GoalTolerances& tolerances);
  /// cancelCB: when `goal` is the active one, hold and report it canceled; true then.
  bool cancelGoal(trajectory::GoalId goal);
  trajectory::GoalId activeGoal() const { return active_goal_; }

  /// query_state: the trajectory sampled at sim time `time` (converted to uptime as upstream);
  /// false with `error` before the trajectory's start or when not running.
  bool queryState(double time, trajectory::State& state, std::string& error) const;
  /// The same on a copy (the ROS side's, for its service thread): `time` and `uptime` those of
  /// the last update.
  static bool sampleTrajectory(const trajectory::Trajectory& trajectory, double sample_uptime,
                               trajectory::State& state, std::string& error);
  const trajectory::Trajectory& currentTrajectory() const { return trajectory_; }
  /// Incremented each time the trajectory is replaced.
  std::uint64_t trajectoryVersion() const { return trajectory_version_; }

  /// updateStates' results of the last update (n joints each; time_from_start as upstream).
  const trajectory::State& desiredState() const { return desired_; }
  const trajectory::State& currentState() const { return current_; }
  const trajectory::State& stateError() const { return error_; }
  /// Sim time and uptime of the last update.
  double time() const { return time_; }
  double uptime() const { return uptime_; }
  /// publishState's schedule: an update strictly later than the last publication +
  /// 1/state_publish_rate of uptime (the last publication moving by the period) leaves a state
  /// to publish; this takes it (its stamp: that update's sim time).
  bool takeStateDue();
  bool running() const { return running_; }

 private:
  void setHold(trajectory::GoalId goal);
  void preemptActiveGoal();
  void finishGoal(GoalEvent::Kind kind, int code, const std::string& text);
  CommandResult updateTrajectoryCommand(const trajectory::JointTrajectoryCommand& command,
                                        trajectory::GoalId goal,
                                        const trajectory::GoalTolerances* tolerances);
  void updateStates();

  std::vector<JointHandle*> joints_;
  std::vector<std::string> joint_names_;
  std::vector<bool> wraparound_;
  trajectory::TrajectoryControllerOptions options_;
  std::vector<Pid> pids_;
  std::vector<double> velocity_ff_;

  trajectory::Trajectory trajectory_;
  trajectory::State desired_, current_, error_;
  double time_ = 0.0;    // sim time of the last update
  double period_ = 0.0;  // its period
  double uptime_ = 0.0;
  double last_state_publish_ = 0.0;
  bool state_due_ = false;
  std::uint64_t trajectory_version_ = 0;
  bool running_ = false;
  trajectory::GoalId active_goal_ = 0;
  std::vector<bool> done_;
  std::vector<GoalEvent> events_;
};

}  // namespace tianracer_control

#endif  // TIANRACER_CONTROL_CONTROLLERS_JOINT_TRAJECTORY_CONTROLLER_H
