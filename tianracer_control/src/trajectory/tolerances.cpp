#include "tianracer_control/trajectory/tolerances.h"

#include <cassert>
#include <cmath>
#include <sstream>

namespace tianracer_control {
namespace trajectory {
namespace {

bool within(double tolerance, double error) {
  return !(tolerance > 0.0 && std::abs(error) > tolerance);
}

bool withinAt(const State& error, std::size_t i, const StateTolerances& tol) {
  return within(tol.position, error.position[i]) && within(tol.velocity, error.velocity[i]) &&
         within(tol.acceleration, error.acceleration[i]);
}

void update(double value, double& tolerance) {
  if (value > 0.0) {
    tolerance = value;
  } else if (value < 0.0) {
    tolerance = 0.0;
  }
}

double readTolerance(ControllerParams& params, const std::string& key, double fallback) {
  const std::optional<double> value = params.number(key);
  if (!value) return fallback;
  if (!std::isfinite(*value) || *value < 0.0) {
    std::ostringstream msg;
    msg << params.prefix() << key << " must be a finite number >= 0 (0 = not enforced), got "
        << *value;
    throw ControllerError(msg.str());
  }
  return *value;
}

}  // namespace

bool checkStateTolerancePerJoint(const State& error, const StateTolerances& tolerance) {
  return withinAt(error, 0, tolerance);
}

bool checkStateTolerance(const State& error, const std::vector<StateTolerances>& tolerance) {
  assert(error.position.size() == tolerance.size());
  for (std::size_t i = 0; i < tolerance.size(); ++i) {
    if (!withinAt(error, i, tolerance[i])) return false;
  }
  return true;
}

void updateStateTolerances(const JointTolerance& msg, StateTolerances& tolerances) {
  update(msg.position, tolerances.position);
  update(msg.velocity, tolerances.velocity);
  update(msg.acceleration, tolerances.acceleration);
}

void updateSegmentTolerances(const GoalTolerances& goal, const std::vector<std::string>& joint_names,
                             SegmentTolerances& tolerances) {
  assert(joint_names.size() == tolerances.state_tolerance.size());
  assert(joint_names.size() == tolerances.goal_state_tolerance.size());
  for (std::size_t i = 0; i < joint_names.size(); ++i) {
    for (const JointTolerance& tol : goal.path_tolerance) {
      if (tol.name == joint_names[i]) updateStateTolerances(tol, tolerances.state_tolerance[i]);
    }
    for (const JointTolerance& tol : goal.goal_tolerance) {
      if (tol.name == joint_names[i]) updateStateTolerances(tol, tolerances.goal_state_tolerance[i]);
    }
  }
  update(goal.goal_time_tolerance, tolerances.goal_time_tolerance);
}

SegmentTolerances readSegmentTolerances(ControllerParams& params,
                                        const std::vector<std::string>& joint_names) {
  SegmentTolerances tolerances(joint_names.size());
  const double stopped_velocity =
      readTolerance(params, "constraints/stopped_velocity_tolerance", 0.01);
  for (std::size_t i = 0; i < joint_names.size(); ++i) {
    const std::string base = "constraints/" + joint_names[i] + "/";
    tolerances.state_tolerance[i].position = readTolerance(params, base + "trajectory", 0.0);
    tolerances.goal_state_tolerance[i].position = readTolerance(params, base + "goal", 0.0);
    tolerances.goal_state_tolerance[i].velocity = stopped_velocity;
  }
  tolerances.goal_time_tolerance = readTolerance(params, "constraints/goal_time", 0.0);
  return tolerances;
}

}  // namespace trajectory
}  // namespace tianracer_control
