// joint_trajectory_controller's trajectory from a command (ros_controllers noetic-devel,
// init_joint_trajectory.h, joint_trajectory_segment.h, joint_trajectory_msg_utils.h): the
// points of a trajectory_msgs/JointTrajectory turned into per-joint segments that replace the
// current trajectory from the first point after now. ROS-free: plain structs in and out.
#ifndef TIANRACER_CONTROL_TRAJECTORY_JOINT_TRAJECTORY_H
#define TIANRACER_CONTROL_TRAJECTORY_JOINT_TRAJECTORY_H

#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "tianracer_control/trajectory/spline_segment.h"
#include "tianracer_control/trajectory/tolerances.h"

namespace tianracer_control {
namespace trajectory {

/// trajectory_msgs/JointTrajectoryPoint without ROS (efforts are not used by the controller).
struct TrajectoryPoint {
  std::vector<double> positions;
  std::vector<double> velocities;     // empty = not given
  std::vector<double> accelerations;  // empty = not given
  double time_from_start = 0.0;       // [s]
};

/// trajectory_msgs/JointTrajectory without ROS.
struct JointTrajectoryCommand {
  double stamp = 0.0;  // header.stamp [s]; 0 = start "now" (the time given to initJointTrajectory)
  std::vector<std::string> joint_names;
  std::vector<TrajectoryPoint> points;
};

/// An action goal a segment belongs to; 0 = none (a topic command, the hold trajectory).
using GoalId = std::uint64_t;

/// One joint's segment (JointTrajectorySegment): the spline, the goal it was made for and that
/// goal's tolerances for this joint.
class JointSegment : public SplineSegment {
 public:
  JointSegment() = default;
  JointSegment(double start_time, const State& start_state, double end_time,
               const State& end_state)
      : SplineSegment(start_time, start_state, end_time, end_state) {}

  GoalId goal() const { return goal_; }
  void setGoal(GoalId goal) { goal_ = goal; }
  const SegmentTolerancesPerJoint& tolerances() const { return tolerances_; }
  void setTolerances(const SegmentTolerancesPerJoint& tolerances) { tolerances_ = tolerances; }

 private:
  GoalId goal_ = 0;
  SegmentTolerancesPerJoint tolerances_;
};

/// Per joint (the controller's order), its segments sorted by start time.
using JointSegments = std::vector<JointSegment>;
using Trajectory = std::vector<JointSegments>;

/// One joint's state from a point (JointTrajectorySegment::State): its position plus `offset`
/// (the wraparound offset), its velocity and acceleration where given, time_from_start.
State jointState(const TrajectoryPoint& point, std::size_t joint, double offset = 0.0);

/// angles::shortest_angular_distance(from, to): to - from wrapped into (-pi, pi].
double shortestAngularDistance(double from, double to);

/// wraparoundJointOffset: for a continuous joint, the multiple of 2 pi to add to `next` so that
/// going there from `prev` takes the short way round (at exactly pi apart: the way `next` lies,
/// as upstream); 0 for other joints.
double wraparoundOffset(double prev, double next, bool wraps);

/// initJointTrajectory's options (InitJointTrajectoryOptions; a goal id stands for the goal
/// handle).
struct InitOptions {
  const Trajectory* current_trajectory = nullptr;  // kept up to the new one's first point
  const std::vector<std::string>* joint_names = nullptr;  // the controller's; else the command's
  const std::vector<bool>* angle_wraparound = nullptr;    // continuous joints, controller order
  GoalId goal = 0;                                        // 0: a topic command
  const GoalTolerances* goal_tolerances = nullptr;        // the action goal's, over the defaults
  const SegmentTolerances* default_tolerances = nullptr;  // the `constraints` parameters
  /// `now` in the time base of current_trajectory (the controller's uptime); unset = the same
  /// base as the command.
  std::optional<double> other_time_base;
  bool allow_partial_joints_goal = false;
};

/// What initJointTrajectory gives: the new trajectory, or an empty one and `error` (upstream's
/// message); `warnings` for what it logs as warnings (points dropped from the past, ...).
struct InitResult {
  Trajectory trajectory;
  std::string error;
  std::vector<std::string> warnings;
  bool ok() const { return error.empty(); }
};

/// The rules of init_joint_trajectory.h. `now` is the command time base's time from which
/// points count (the controller passes the time of its next update):
///  - the trajectory starts at `stamp`, or at `now` when stamp is 0;
///  - rejected, with upstream's message: no points ("Trajectory message contains empty
///    trajectory. Nothing to convert."), times not strictly increasing, a wraparound vector of
///    the wrong size, joints that are not the controller's or (without allow_partial_joints_goal)
///    not all of them ("... It does not contain the expected joints."), every point at or before
///    now ("Dropping all N trajectory point(s), as they occur before the current time.\nLast
///    point is X s in the past."), a point whose lists have the wrong size;
///  - rejected here too (upstream reads out of bounds, or throws later): a joint named twice, a
///    point without positions, a non-finite value or time, and a single point with no current
///    trajectory to bridge from (upstream returns an empty trajectory without a message);
///  - points at or before now are dropped (a warning, except the usual first point at
///    time_from_start 0 of a command stamped 0);
///  - with a current trajectory, per joint commanded: its segments from the one active at now
///    to the one active when the new trajectory starts are kept, then a bridge segment from
///    the current trajectory's state at max(start, now) to the first new point, then the new
///    segments; for a continuous joint every new position is shifted by the wraparound offset
///    between the current state and the first new point;
///  - joints not commanded (a partial goal) keep the current trajectory, its segments from now
///    on given to the new goal;
///  - segments of an action goal carry its tolerances: the defaults with the goal's over them.
InitResult initJointTrajectory(const JointTrajectoryCommand& command, double now,
                               const InitOptions& options = InitOptions());

/// The hold trajectory (HoldTrajectoryBuilder, stop_trajectory_duration 0): per joint one
/// segment of zero length at `time`, at `positions[i]`, velocity and acceleration 0.
Trajectory holdTrajectory(double time, const std::vector<double>& positions, GoalId goal = 0);

/// The stop trajectory (StopTrajectoryBuilder, stop_trajectory_duration > 0): per joint from the
/// desired state (position p, velocity v, acceleration 0) at `time` to rest within `duration`:
/// the quintic from (p, v, 0) to (p, -v, 0) over 2 duration, sampled at its middle (zero
/// velocity by symmetry) gives the end state; the segment goes there in `duration`.
Trajectory stopTrajectory(double time, double duration, const State& desired, GoalId goal = 0);

/// The state error the controller checks (updateStates): position
/// shortestAngularDistance(actual, desired) -- for every joint, continuous or not, as upstream --,
/// velocity desired - actual, acceleration 0.
State stateError(const State& desired, const State& actual);

/// What the update loop's tolerance checks decide for the active goal.
struct GoalCheck {
  enum class Outcome { kRunning, kSucceeded, kPathToleranceViolated, kGoalToleranceViolated };
  Outcome outcome = Outcome::kRunning;
  /// FollowJointTrajectoryResult's error_code: 0, -4 (PATH_TOLERANCE_VIOLATED) or -5 (GOAL_...).
  int error_code = 0;
  std::string error_string;  // "<joint> path error <e>" / "<joint> goal error <e>"
};

/// The checks of JointTrajectoryController::update() for the active goal `goal` at `uptime`,
/// joint by joint, on the segment active for each: while a segment of the goal runs
/// (uptime < its end) the path tolerances; on the goal's last segment the goal tolerances,
/// met -> that joint done (`done`, one flag per joint, kept between calls), not met after
/// end + goal_time_tolerance -> aborted. All joints done -> succeeded. `error` holds the
/// state error of every joint (stateError). A joint without a segment at `uptime` is skipped.
GoalCheck checkGoal(const Trajectory& trajectory, double uptime, const State& error, GoalId goal,
                    const std::vector<std::string>& joint_names, std::vector<bool>& done);

}  // namespace trajectory
}  // namespace tianracer_control

#endif  // TIANRACER_CONTROL_TRAJECTORY_JOINT_TRAJECTORY_H
