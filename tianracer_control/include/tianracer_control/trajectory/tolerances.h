// joint_trajectory_controller's tolerances (ros_controllers noetic-devel, tolerances.h): path and
// goal tolerances per joint, the goal time tolerance, the `constraints` parameter tree, and an
// action goal's tolerances over the defaults. ROS-free.
#ifndef TIANRACER_CONTROL_TRAJECTORY_TOLERANCES_H
#define TIANRACER_CONTROL_TRAJECTORY_TOLERANCES_H

#include <string>
#include <vector>

#include "tianracer_control/controller_params.h"
#include "tianracer_control/trajectory/spline_segment.h"

namespace tianracer_control {
namespace trajectory {

/// Tolerances on one joint's position, velocity and acceleration error; 0 = not enforced.
struct StateTolerances {
  double position = 0.0;
  double velocity = 0.0;
  double acceleration = 0.0;
};

/// The tolerances of a trajectory, per joint in the controller's joint order.
struct SegmentTolerances {
  SegmentTolerances() = default;
  explicit SegmentTolerances(std::size_t n) : state_tolerance(n), goal_state_tolerance(n) {}

  std::vector<StateTolerances> state_tolerance;       // while a segment runs (path)
  std::vector<StateTolerances> goal_state_tolerance;  // at the end of the last segment
  double goal_time_tolerance = 0.0;  // extra time after the end to get within the goal [s]
};

/// The same for one joint, as each segment carries them.
struct SegmentTolerancesPerJoint {
  StateTolerances state_tolerance;
  StateTolerances goal_state_tolerance;
  double goal_time_tolerance = 0.0;
};

/// True when |error| <= tolerance for each of position, velocity and acceleration whose
/// tolerance is > 0 (checkStateTolerancePerJoint; `error` holds one joint at index 0).
bool checkStateTolerancePerJoint(const State& error, const StateTolerances& tolerance);
/// The same over all joints (checkStateTolerance): `error` holds n joints.
bool checkStateTolerance(const State& error, const std::vector<StateTolerances>& tolerance);

/// control_msgs/JointTolerance without ROS.
struct JointTolerance {
  std::string name;
  double position = 0.0;
  double velocity = 0.0;
  double acceleration = 0.0;
};

/// The tolerance fields of a control_msgs/FollowJointTrajectoryGoal.
struct GoalTolerances {
  std::vector<JointTolerance> path_tolerance;
  std::vector<JointTolerance> goal_tolerance;
  double goal_time_tolerance = 0.0;  // [s]
};

/// updateStateTolerances: per field, a value > 0 replaces the tolerance, < 0 resets it to 0
/// (not enforced), 0 keeps it.
void updateStateTolerances(const JointTolerance& msg, StateTolerances& tolerances);
/// updateSegmentTolerances: an action goal's tolerances over `tolerances` (the defaults), joints
/// matched by name (entries for other joints are ignored, as upstream); goal_time_tolerance
/// > 0 replaces, < 0 resets to 0, 0 keeps. `tolerances` has one entry per name of
/// `joint_names`.
void updateSegmentTolerances(const GoalTolerances& goal, const std::vector<std::string>& joint_names,
                             SegmentTolerances& tolerances);

/// The `constraints` parameter tree under the controller (getSegmentTolerances):
///   constraints:
///     goal_time: 0.5                     # goal_time_tolerance, default 0
///     stopped_velocity_tolerance: 0.02   # every joint's goal velocity tolerance, default 0.01
///     <joint>: {trajectory: 0.05, goal: 0.03}   # position path / goal tolerance, default 0
/// Upstream takes any value; here a negative or non-finite value, or one that is no number,
/// throws ControllerError naming the key and the value (a negative tolerance would silently
/// mean "not enforced").
SegmentTolerances readSegmentTolerances(ControllerParams& params,
                                        const std::vector<std::string>& joint_names);

}  // namespace trajectory
}  // namespace tianracer_control

#endif  // TIANRACER_CONTROL_TRAJECTORY_TOLERANCES_H
