// joint_trajectory_controller's tolerances (tolerances.h): the checks, an action goal's values
// over the defaults, and the `constraints` parameter tree, with the cases and the YAML of
// ros_controllers' tolerances_test.cpp / tolerances.yaml; and the controller's other parameters.
#include <cmath>
#include <limits>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "tianracer_control/trajectory/controller_options.h"
#include "tianracer_control/trajectory/tolerances.h"

using namespace tianracer_control;              // NOLINT: test file
using namespace tianracer_control::trajectory;  // NOLINT: test file

namespace {

State errorOf(double p, double v, double a) {
  State s(2);
  s.position = {0.5, p};
  s.velocity = {0.5, v};
  s.acceleration = {0.5, a};
  return s;
}

// Each tolerance is checked on its own; 0 = not enforced; the bound itself passes.
TEST(TrajectoryTolerances, CheckStateTolerance) {
  const double tol = 1.0;
  const State ok = errorOf(tol / 2, tol / 2, tol / 2);
  std::vector<StateTolerances> none(2);
  EXPECT_TRUE(checkStateTolerance(errorOf(9, 9, 9), none));

  for (int field = 0; field < 3; ++field) {
    std::vector<StateTolerances> tols(2);
    double* fields[] = {&tols[1].position, &tols[1].velocity, &tols[1].acceleration};
    *fields[field] = tol;
    EXPECT_TRUE(checkStateTolerance(ok, tols)) << field;
    State other = ok;
    std::vector<double>* values[] = {&other.position, &other.velocity, &other.acceleration};
    for (int f = 0; f < 3; ++f) {
      if (f != field) values[f]->back() *= 4.0;  // the unchecked ones may be off
    }
    EXPECT_TRUE(checkStateTolerance(other, tols)) << field;
    values[field]->back() = -tol;  // |e| == tol passes
    EXPECT_TRUE(checkStateTolerance(other, tols)) << field;
    values[field]->back() = -2.0 * tol;
    EXPECT_FALSE(checkStateTolerance(other, tols)) << field;
    State joint(1);
    joint.position[0] = other.position[1];
    joint.velocity[0] = other.velocity[1];
    joint.acceleration[0] = other.acceleration[1];
    EXPECT_FALSE(checkStateTolerancePerJoint(joint, tols[1])) << field;
  }
}

TEST(TrajectoryTolerances, UpdateStateTolerances) {
  const StateTolerances defaults{1.0, 2.0, 3.0};
  StateTolerances t = defaults;
  updateStateTolerances({"foo_joint", 0.0, 0.0, 0.0}, t);  // zero: no change
  EXPECT_EQ(t.position, 1.0);
  EXPECT_EQ(t.velocity, 2.0);
  EXPECT_EQ(t.acceleration, 3.0);
  updateStateTolerances({"foo_joint", -1.0, 0.0, 0.0}, t);  // negative: reset
  EXPECT_EQ(t.position, 0.0);
  EXPECT_EQ(t.velocity, 2.0);
  t = defaults;
  updateStateTolerances({"foo_joint", 0.0, -1.0, -1.0}, t);
  EXPECT_EQ(t.position, 1.0);
  EXPECT_EQ(t.velocity, 0.0);
  EXPECT_EQ(t.acceleration, 0.0);
  t = defaults;
  updateStateTolerances({"foo_joint", 4.0, 5.0, 6.0}, t);  // positive: replace
  EXPECT_EQ(t.position, 4.0);
  EXPECT_EQ(t.velocity, 5.0);
  EXPECT_EQ(t.acceleration, 6.0);
}

TEST(TrajectoryTolerances, UpdateSegmentTolerancesByName) {
  const std::vector<std::string> joints = {"foo_joint", "bar_joint"};
  SegmentTolerances tols(2);
  tols.state_tolerance[1].position = 0.5;
  tols.goal_time_tolerance = 1.0;
  GoalTolerances goal;
  goal.path_tolerance = {{"bar_joint", 1.0, 0.0, 0.0}, {"baz_joint", 9.0, 9.0, 9.0}};
  goal.goal_tolerance = {{"foo_joint", 0.0, 2.0, 0.0}};
  updateSegmentTolerances(goal, joints, tols);
  EXPECT_EQ(tols.state_tolerance[0].position, 0.0);
  EXPECT_EQ(tols.state_tolerance[1].position, 1.0);
  EXPECT_EQ(tols.goal_state_tolerance[0].velocity, 2.0);
  EXPECT_EQ(tols.goal_state_tolerance[1].velocity, 0.0);
  EXPECT_EQ(tols.goal_time_tolerance, 1.0);  // 0: kept
  goal.goal_time_tolerance = 2.5;
  updateSegmentTolerances(goal, joints, tols);
  EXPECT_EQ(tols.goal_time_tolerance, 2.5);
  goal.goal_time_tolerance = -1.0;
  updateSegmentTolerances(goal, joints, tols);
  EXPECT_EQ(tols.goal_time_tolerance, 0.0);
}

ControllerSpec trajectorySpec() {
  ControllerSpec s;
  s.name = "arm_controller";
  s.type = "position_controllers/JointTrajectoryController";
  return s;
}

// ros_controllers' test/tolerances.yaml.
TEST(TrajectoryTolerances, ConstraintsParameters) {
  ControllerSpec s = trajectorySpec();
  ParamValue& c = s.params["constraints"];
  c["goal_time"] = 1.0;
  c["stopped_velocity_tolerance"] = 0.02;
  c["foo_joint"]["trajectory"] = 0.05;
  c["foo_joint"]["goal"] = 0.03;
  c["bar_joint"]["goal"] = 0.01;
  c["baz_joint"]["trajectory"] = 1.0;  // not one of the joints
  c["baz_joint"]["goal"] = 2.0;
  ControllerParams params(s);
  const SegmentTolerances t = readSegmentTolerances(params, {"foo_joint", "bar_joint"});
  EXPECT_EQ(t.goal_time_tolerance, 1.0);
  ASSERT_EQ(t.state_tolerance.size(), 2u);
  EXPECT_EQ(t.state_tolerance[0].position, 0.05);
  EXPECT_EQ(t.state_tolerance[0].velocity, 0.0);
  EXPECT_EQ(t.state_tolerance[0].acceleration, 0.0);
  EXPECT_EQ(t.goal_state_tolerance[0].position, 0.03);
  EXPECT_EQ(t.goal_state_tolerance[0].velocity, 0.02);
  EXPECT_EQ(t.goal_state_tolerance[0].acceleration, 0.0);
  EXPECT_EQ(t.state_tolerance[1].position, 0.0);
  EXPECT_EQ(t.goal_state_tolerance[1].position, 0.01);
  EXPECT_EQ(t.goal_state_tolerance[1].velocity, 0.02);
  // The keys of a joint the controller does not have are left for the unknown-key report.
  EXPECT_EQ(params.unread(), std::vector<std::string>({"constraints/baz_joint"}));
}

TEST(TrajectoryTolerances, ConstraintsDefaults) {
  ControllerSpec s = trajectorySpec();
  ControllerParams params(s);
  const SegmentTolerances t = readSegmentTolerances(params, {"foo_joint"});
  EXPECT_EQ(t.goal_time_tolerance, 0.0);
  EXPECT_EQ(t.state_tolerance[0].position, 0.0);
  EXPECT_EQ(t.goal_state_tolerance[0].position, 0.0);
  EXPECT_EQ(t.goal_state_tolerance[0].velocity, 0.01);
}

std::string constraintsError(const std::string& key, ParamValue value) {
  ControllerSpec s = trajectorySpec();
  ParamValue* node = &s.params["constraints"];
  std::size_t slash;
  std::string rest = key;
  while ((slash = rest.find('/')) != std::string::npos) {
    node = &(*node)[rest.substr(0, slash)];
    rest = rest.substr(slash + 1);
  }
  (*node)[rest] = value;
  ControllerParams params(s);
  try {
    readSegmentTolerances(params, {"foo_joint"});
  } catch (const ControllerError& e) {
    return e.what();
  }
  return "";
}

TEST(TrajectoryTolerances, BadConstraintsNameKeyAndValue) {
  EXPECT_EQ(constraintsError("foo_joint/goal", -0.1),
            "controller 'arm_controller': constraints/foo_joint/goal must be a finite number >= 0 "
            "(0 = not enforced), got -0.1");
  EXPECT_EQ(constraintsError("goal_time", std::numeric_limits<double>::infinity()),
            "controller 'arm_controller': constraints/goal_time must be a finite number >= 0 "
            "(0 = not enforced), got inf");
  EXPECT_EQ(constraintsError("stopped_velocity_tolerance", "fast"),
            "controller 'arm_controller': constraints/stopped_velocity_tolerance must be a "
            "number, got a string");
  EXPECT_EQ(constraintsError("foo_joint/trajectory", 1), "");  // an int is a number
}

TEST(TrajectoryControllerOptions, DefaultsAndValues) {
  ControllerSpec s = trajectorySpec();
  {
    ControllerParams params(s);
    const TrajectoryControllerOptions o = readTrajectoryControllerOptions(params, {"foo_joint"});
    EXPECT_EQ(o.state_publish_rate, 50.0);
    EXPECT_EQ(o.action_monitor_rate, 20.0);
    EXPECT_EQ(o.stop_trajectory_duration, 0.0);
    EXPECT_FALSE(o.allow_partial_joints_goal);
    EXPECT_EQ(o.default_tolerances.goal_state_tolerance.at(0).velocity, 0.01);
  }
  s.params["state_publish_rate"] = 25;
  s.params["action_monitor_rate"] = 10.0;
  s.params["stop_trajectory_duration"] = 0.2;
  s.params["allow_partial_joints_goal"] = true;
  ControllerParams params(s);
  const TrajectoryControllerOptions o = readTrajectoryControllerOptions(params, {"foo_joint"});
  EXPECT_EQ(o.state_publish_rate, 25.0);
  EXPECT_EQ(o.action_monitor_rate, 10.0);
  EXPECT_EQ(o.stop_trajectory_duration, 0.2);
  EXPECT_TRUE(o.allow_partial_joints_goal);
  EXPECT_TRUE(params.unread().empty());
}

TEST(TrajectoryControllerOptions, BadValues) {
  auto error = [](const std::string& key, ParamValue value) {
    ControllerSpec s = trajectorySpec();
    s.params[key] = value;
    ControllerParams params(s);
    try {
      readTrajectoryControllerOptions(params, {"foo_joint"});
    } catch (const ControllerError& e) {
      return std::string(e.what());
    }
    return std::string();
  };
  EXPECT_EQ(error("state_publish_rate", 0.0),
            "controller 'arm_controller': state_publish_rate must be a finite rate > 0 [Hz], got 0");
  EXPECT_EQ(error("action_monitor_rate", -5.0),
            "controller 'arm_controller': action_monitor_rate must be a finite rate > 0 [Hz], got -5");
  EXPECT_EQ(error("stop_trajectory_duration", -0.1),
            "controller 'arm_controller': stop_trajectory_duration must be a finite duration >= 0 "
            "[s], got -0.1");
  EXPECT_EQ(error("stop_trajectory_duration", 0.0), "");
  EXPECT_EQ(error("allow_partial_joints_goal", 1.5),
            "controller 'arm_controller': allow_partial_joints_goal must be true or false, got a double");
}

}  // namespace
