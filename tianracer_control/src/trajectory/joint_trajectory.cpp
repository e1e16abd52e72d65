#include "tianracer_control/trajectory/joint_trajectory.h"

#include <algorithm>
#include <cmath>
#include <iomanip>
#include <sstream>
#include <stdexcept>

namespace tianracer_control {
namespace trajectory {
namespace {

constexpr const char* kNotExpectedJoints =
    "Cannot create trajectory from message. It does not contain the expected joints.";
constexpr const char* kSizeMismatch =
    "Size mismatch in trajectory point position, velocity or acceleration data.";

// angles::normalize_angle: into (-pi, pi].
double normalizeAngle(double angle) {
  const double result = std::fmod(angle + M_PI, 2.0 * M_PI);
  return result <= 0.0 ? result + M_PI : result - M_PI;
}

bool listOk(const std::vector<double>& values, std::size_t n) {
  return values.empty() || values.size() == n;
}

bool allFinite(const std::vector<double>& values) {
  return std::all_of(values.begin(), values.end(), [](double v) { return std::isfinite(v); });
}

// The message's checks that do not depend on the controller, in upstream's order where upstream
// has them; "" when the command is usable.
std::string checkCommand(const JointTrajectoryCommand& command) {
  if (command.points.empty()) return "Trajectory message contains empty trajectory. Nothing to convert.";
  for (std::size_t k = 1; k < command.points.size(); ++k) {
    if (!(command.points[k - 1].time_from_start < command.points[k].time_from_start)) {
      return "Trajectory message contains waypoints that are not strictly increasing in time.";
    }
  }
  const std::size_t n = command.joint_names.size();
  for (std::size_t i = 0; i < n; ++i) {
    for (std::size_t j = 0; j < i; ++j) {
      if (command.joint_names[i] == command.joint_names[j]) {
        return "Cannot create trajectory from message. Joint '" + command.joint_names[i] +
               "' is named twice.";
      }
    }
  }
  if (!std::isfinite(command.stamp)) return "Trajectory message has a non-finite header stamp.";
  for (std::size_t k = 0; k < command.points.size(); ++k) {
    const TrajectoryPoint& p = command.points[k];
    std::ostringstream where;
    where << "Invalid trajectory point at index: " << k << ". ";
    if (p.positions.size() != n || !listOk(p.velocities, n) || !listOk(p.accelerations, n)) {
      std::ostringstream msg;
      msg << where.str() << kSizeMismatch << " (" << n << " joint(s); " << p.positions.size()
          << " position(s), " << p.velocities.size() << " velocit(ies), "
          << p.accelerations.size() << " acceleration(s))";
      return msg.str();
    }
    if (!allFinite(p.positions) || !allFinite(p.velocities) || !allFinite(p.accelerations) ||
        !std::isfinite(p.time_from_start)) {
      return where.str() + "It holds a non-finite value (nan or inf).";
    }
  }
  return "";
}

// Index of each command joint among `expected` (internal::mapping); empty when the command has
// more joints or one that is not expected.
std::vector<std::size_t> mapping(const std::vector<std::string>& names,
                                 const std::vector<std::string>& expected) {
  if (names.size() > expected.size()) return {};
  std::vector<std::size_t> result(names.size());
  for (std::size_t i = 0; i < names.size(); ++i) {
    const auto it = std::find(expected.begin(), expected.end(), names[i]);
    if (it == expected.end()) return {};
    result[i] = static_cast<std::size_t>(it - expected.begin());
  }
  return result;
}

std::string fixed3(double value) {
  std::ostringstream out;
  out << std::fixed << std::setprecision(3) << value;
  return out.str();
}

InitResult fail(InitResult result, std::string error) {
  result.trajectory.clear();
  result.error = std::move(error);
  return result;
}

}  // namespace

State jointState(const TrajectoryPoint& point, std::size_t joint, double offset) {
  State state;
  state.position.assign(1, point.positions.at(joint) + offset);
  if (!point.velocities.empty()) state.velocity.assign(1, point.velocities.at(joint));
  if (!point.accelerations.empty()) state.acceleration.assign(1, point.accelerations.at(joint));
  state.time_from_start = point.time_from_start;
  return state;
}

double shortestAngularDistance(double from, double to) { return normalizeAngle(to - from); }

double wraparoundOffset(double prev, double next, bool wraps) {
  if (!wraps) return 0.0;
  double dist = shortestAngularDistance(prev, next);
  // At exactly pi apart either way is shortest: take the one towards where `next` lies.
  if (std::abs(std::abs(dist) - M_PI) < 1e-9) {
    dist = next > prev ? std::abs(dist) : -std::abs(dist);
  }
  return (prev + dist) - next;
}

InitResult initJointTrajectory(const JointTrajectoryCommand& command, double now,
                               const InitOptions& options) {
  InitResult result;
  const std::string invalid = checkCommand(command);
  if (!invalid.empty()) return fail(std::move(result), invalid);

  const double msg_start_time = command.stamp == 0.0 ? now : command.stamp;
  const bool has_current = options.current_trajectory && !options.current_trajectory->empty();
  const bool has_joint_names = options.joint_names && !options.joint_names->empty();
  const bool has_wraparound = options.angle_wraparound && !options.angle_wraparound->empty();
  if (!has_current && has_wraparound) {
    result.warnings.push_back(
        "Vector specifying whether joints wrap around will not be used because no current "
        "trajectory was given.");
  }

  // Times in the current trajectory's base ("o_" upstream).
  const double o_time = options.other_time_base ? *options.other_time_base : now;
  const double o_msg_start_time = o_time + (msg_start_time - now);

  const std::vector<std::string>& joint_names =
      has_joint_names ? *options.joint_names : command.joint_names;
  if (has_wraparound && options.angle_wraparound->size() != joint_names.size()) {
    return fail(std::move(result),
                "Cannot create trajectory from message. Vector specifying whether joints wrap "
                "around has an invalid size.");
  }
  if (has_current && options.current_trajectory->size() != joint_names.size()) {
    throw std::invalid_argument("initJointTrajectory: the current trajectory has " +
                                std::to_string(options.current_trajectory->size()) +
                                " joint(s), the controller " + std::to_string(joint_names.size()));
  }
  if (!options.allow_partial_joints_goal && command.joint_names.size() != joint_names.size()) {
    return fail(std::move(result), kNotExpectedJoints);
  }
  const std::vector<std::size_t> map = mapping(command.joint_names, joint_names);
  if (map.empty()) return fail(std::move(result), kNotExpectedJoints);

  SegmentTolerances tolerances = options.default_tolerances ? *options.default_tolerances
                                                            : SegmentTolerances(joint_names.size());
  if (tolerances.state_tolerance.size() != joint_names.size() ||
      tolerances.goal_state_tolerance.size() != joint_names.size()) {
    throw std::invalid_argument("initJointTrajectory: default tolerances for " +
                                std::to_string(tolerances.state_tolerance.size()) +
                                " joint(s), the controller has " +
                                std::to_string(joint_names.size()));
  }
  if (options.goal != 0 && options.goal_tolerances) {
    updateSegmentTolerances(*options.goal_tolerances, joint_names, tolerances);
  }

  // The first point after now (findPoint: the last point at or before now, then one on).
  const auto& points = command.points;
  std::size_t first = 0;
  while (first < points.size() && !(now < msg_start_time + points[first].time_from_start)) ++first;
  if (first == points.size()) {
    std::ostringstream msg;
    msg << "Dropping all " << points.size()
        << " trajectory point(s), as they occur before the current time.\nLast point is "
        << std::to_string(now - (msg_start_time + points.back().time_from_start))
        << "s in the past.";
    return fail(std::move(result), msg.str());
  }
  if (first > 0 &&
      !(first == 1 && points.front().time_from_start == 0.0 && command.stamp == 0.0)) {
    std::ostringstream msg;
    msg << "Dropping first " << first << " trajectory point(s) out of " << points.size()
        << ", as they occur before the current time.\nFirst valid point will be reached in "
        << fixed3(msg_start_time + points[first].time_from_start - now) << "s.";
    result.warnings.push_back(msg.str());
  }
  if (!has_current && points.size() - first < 2) {
    return fail(std::move(result),
                "Trajectory message has a single point after the current time and there is no "
                "current trajectory to go to it from.");
  }

  // Joints not commanded keep the current trajectory; its segments from now on go to the goal.
  if (has_current) {
    result.trajectory = *options.current_trajectory;
    for (JointSegments& segments : result.trajectory) {
      auto active = findSegment(segments, o_time);
      for (auto it = active; it != segments.end(); ++it) {
        segments[static_cast<std::size_t>(it - segments.begin())].setGoal(options.goal);
      }
    }
  } else {
    result.trajectory.resize(joint_names.size());
  }

  for (std::size_t k = 0; k < map.size(); ++k) {
    const std::size_t joint = map[k];
    JointSegments segments;
    double offset = 0.0;
    SegmentTolerancesPerJoint joint_tolerances;
    joint_tolerances.state_tolerance = tolerances.state_tolerance[joint];
    joint_tolerances.goal_state_tolerance = tolerances.goal_state_tolerance[joint];
    joint_tolerances.goal_time_tolerance = tolerances.goal_time_tolerance;

    if (has_current) {
      const JointSegments& current = (*options.current_trajectory)[joint];
      const double last_curr_time = std::max(o_msg_start_time, o_time);
      State last_curr_state;
      sampleSegments(current, last_curr_time, last_curr_state);

      const double first_new_time = o_msg_start_time + points[first].time_from_start;
      if (has_wraparound) {
        offset = wraparoundOffset(last_curr_state.position.at(0), points[first].positions[k],
                                  (*options.angle_wraparound)[joint]);
      }
      const State first_new_state = jointState(points[first], k, offset);

      const auto from = findSegment(current, o_time);
      const auto to = findSegment(current, last_curr_time);
      if (from == current.end() || to == current.end()) {
        return fail(std::move(result),
                    "Unexpected error: Could not find segments in current trajectory. Please "
                    "contact the package maintainer.");
      }
      segments.insert(segments.end(), from, to + 1);  // still executed

      JointSegment bridge(last_curr_time, last_curr_state, first_new_time, first_new_state);
      bridge.setGoal(options.goal);
      if (options.goal != 0) bridge.setTolerances(joint_tolerances);
      segments.push_back(bridge);
    }

    for (std::size_t p = first; p + 1 < points.size(); ++p) {
      const State start = jointState(points[p], k, offset);
      const State end = jointState(points[p + 1], k, offset);
      JointSegment segment(o_msg_start_time + points[p].time_from_start, start,
                           o_msg_start_time + points[p + 1].time_from_start, end);
      segment.setGoal(options.goal);
      if (options.goal != 0) segment.setTolerances(joint_tolerances);
      segments.push_back(segment);
    }
    if (!segments.empty()) result.trajectory[joint] = std::move(segments);
  }

  const bool all_empty = std::all_of(result.trajectory.begin(), result.trajectory.end(),
                                     [](const JointSegments& s) { return s.empty(); });
  if (all_empty) result.trajectory.clear();
  return result;
}

Trajectory holdTrajectory(double time, const std::vector<double>& positions, GoalId goal) {
  Trajectory trajectory(positions.size());
  State state(1);
  for (std::size_t i = 0; i < positions.size(); ++i) {
    state.position[0] = positions[i];
    JointSegment segment(time, state, time, state);
    segment.setGoal(goal);
    trajectory[i].push_back(segment);
  }
  return trajectory;
}

Trajectory stopTrajectory(double time, double duration, const State& desired, GoalId goal) {
  if (!(duration > 0.0) || !std::isfinite(duration)) {
    throw std::invalid_argument("stopTrajectory: the duration must be > 0, got " +
                                std::to_string(duration));
  }
  if (desired.velocity.size() != desired.position.size()) {
    throw std::invalid_argument("stopTrajectory: the desired state needs a velocity per joint");
  }
  Trajectory trajectory(desired.position.size());
  State start(1), mirrored(1), rest;
  for (std::size_t i = 0; i < desired.position.size(); ++i) {
    start.position[0] = desired.position[i];
    start.velocity[0] = desired.velocity[i];
    mirrored.position[0] = desired.position[i];
    mirrored.velocity[0] = -desired.velocity[i];
    JointSegment segment(time, start, time + 2.0 * duration, mirrored);
    segment.sample(time + duration, rest);
    segment.init(time, start, time + duration, rest);
    segment.setGoal(goal);
    trajectory[i].push_back(segment);
  }
  return trajectory;
}

State stateError(const State& desired, const State& actual) {
  const std::size_t n = desired.position.size();
  State error(n);
  for (std::size_t i = 0; i < n; ++i) {
    error.position[i] = shortestAngularDistance(actual.position.at(i), desired.position[i]);
    error.velocity[i] = desired.velocity.at(i) - actual.velocity.at(i);
  }
  return error;
}

GoalCheck checkGoal(const Trajectory& trajectory, double uptime, const State& error, GoalId goal,
                    const std::vector<std::string>& joint_names, std::vector<bool>& done) {
  GoalCheck check;
  const std::size_t n = trajectory.size();
  done.resize(n, false);
  if (goal == 0) return check;
  State joint_error(1);
  for (std::size_t i = 0; i < n; ++i) {
    const JointSegments& segments = trajectory[i];
    const auto it = findSegment(segments, uptime);
    if (it == segments.end() || it->goal() != goal) continue;
    joint_error.position[0] = error.position.at(i);
    joint_error.velocity[0] = error.velocity.at(i);
    joint_error.acceleration[0] = error.acceleration.at(i);
    const std::string& name = joint_names.at(i);
    if (uptime < it->endTime()) {
      if (!checkStateTolerancePerJoint(joint_error, it->tolerances().state_tolerance)) {
        check.outcome = GoalCheck::Outcome::kPathToleranceViolated;
        check.error_code = -4;
        check.error_string = name + " path error " + std::to_string(joint_error.position[0]);
        done.assign(n, false);
        return check;
      }
    } else if (it + 1 == segments.end()) {
      const SegmentTolerancesPerJoint& tol = it->tolerances();
      if (checkStateTolerancePerJoint(joint_error, tol.goal_state_tolerance)) {
        done[i] = true;
      } else if (!(uptime < it->endTime() + tol.goal_time_tolerance)) {
        check.outcome = GoalCheck::Outcome::kGoalToleranceViolated;
        check.error_code = -5;
        check.error_string = name + " goal error " + std::to_string(joint_error.position[0]);
        done.assign(n, false);
        return check;
      }
    }
  }
  if (n > 0 && std::all_of(done.begin(), done.end(), [](bool d) { return d; })) {
    check.outcome = GoalCheck::Outcome::kSucceeded;
    done.assign(n, false);
  }
  return check;
}

}  // namespace trajectory
}  // namespace tianracer_control
