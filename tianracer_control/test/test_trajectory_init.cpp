// A command turned into a trajectory (init_joint_trajectory.h's rules), with the fixture and
// cases of ros_controllers' init_joint_trajectory_test.cpp, and every rejection with its message.
#include <cmath>
#include <limits>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "tianracer_control/trajectory/joint_trajectory.h"

using namespace tianracer_control::trajectory;  // NOLINT: test file

namespace {

TrajectoryPoint point(double p, double t) {
  TrajectoryPoint pt;
  pt.positions = {p};
  pt.velocities = {0.0};
  pt.accelerations = {0.0};
  pt.time_from_start = t;
  return pt;
}

State stateOf(const JointSegment& segment, double t) {
  State s;
  segment.sample(t, s);
  return s;
}

// Upstream's fixture: three points of foo_joint at 1, 2 and 4 s after a stamp of 0.5 s; a current
// trajectory of two segments, 0..1 s and (junk) 3..10 s.
class TrajectoryInit : public ::testing::Test {
 protected:
  TrajectoryInit() {
    command.stamp = 0.5;
    command.joint_names = {"foo_joint"};
    command.points = {point(2.0, 1.0), point(4.0, 2.0), point(3.0, 4.0)};
    State s0 = State(1), s1 = State(1);
    s1.position[0] = s1.velocity[0] = s1.acceleration[0] = 1.0;
    current.push_back({JointSegment(0.0, s0, 1.0, s1), JointSegment(3.0, s1, 10.0, s0)});
  }

  JointTrajectoryCommand command;
  Trajectory current;
};

TEST_F(TrajectoryInit, WithoutCurrentTrajectoryOnlyPointsAfterNow) {
  const double t0 = command.stamp;
  EXPECT_EQ(initJointTrajectory(command, t0).trajectory.at(0).size(), 2u);        // before 1st
  EXPECT_EQ(initJointTrajectory(command, t0 + 1.0).trajectory.at(0).size(), 1u);  // at 1st
  EXPECT_EQ(initJointTrajectory(command, t0 + 1.5).trajectory.at(0).size(), 1u);
  // From the second point on a single point is left and nothing to go to it from.
  for (double t : {2.0, 3.0}) {
    const InitResult r = initJointTrajectory(command, t0 + t);
    EXPECT_TRUE(r.trajectory.empty()) << t;
    EXPECT_EQ(r.error,
              "Trajectory message has a single point after the current time and there is no "
              "current trajectory to go to it from.");
  }
  for (double t : {4.0, 5.0}) {
    EXPECT_TRUE(initJointTrajectory(command, t0 + t).trajectory.empty()) << t;
  }
}

TEST_F(TrajectoryInit, EveryPointInThePastIsRejected) {
  const InitResult r = initJointTrajectory(command, command.stamp + 5.0);
  EXPECT_FALSE(r.ok());
  EXPECT_EQ(r.error,
            "Dropping all 3 trajectory point(s), as they occur before the current time.\n"
            "Last point is 1.000000s in the past.");
}

TEST_F(TrajectoryInit, DroppedPointsAreWarned) {
  const InitResult r = initJointTrajectory(command, command.stamp + 1.5);
  ASSERT_TRUE(r.ok());
  ASSERT_EQ(r.warnings.size(), 1u);
  EXPECT_EQ(r.warnings[0],
            "Dropping first 1 trajectory point(s) out of 3, as they occur before the current "
            "time.\nFirst valid point will be reached in 0.500s.");
}

// Stamp 0: the trajectory starts now; a first point at time_from_start 0 is dropped silently.
TEST_F(TrajectoryInit, StampZeroMeansNow) {
  command.stamp = 0.0;
  command.points.insert(command.points.begin(), point(1.0, 0.0));
  const double now = 7.0;
  const InitResult r = initJointTrajectory(command, now);
  ASSERT_TRUE(r.ok()) << r.error;
  EXPECT_TRUE(r.warnings.empty());
  ASSERT_EQ(r.trajectory.at(0).size(), 2u);
  EXPECT_EQ(r.trajectory[0][0].startTime(), now + 1.0);
  EXPECT_EQ(r.trajectory[0][1].endTime(), now + 4.0);
}

TEST_F(TrajectoryInit, WithCurrentTrajectoryKeepsItUpToTheBridge) {
  InitOptions options;
  options.current_trajectory = &current;
  const double t0 = command.stamp;
  auto count = [&](double now) {
    const InitResult r = initJointTrajectory(command, now, options);
    return r.trajectory.empty() ? 0u : r.trajectory.at(0).size();
  };
  EXPECT_EQ(count(0.0), 4u);       // current's first + bridge + 2 new
  EXPECT_EQ(count(t0), 4u);
  EXPECT_EQ(count(t0 + 1.0), 3u);  // current + bridge + last new
  EXPECT_EQ(count(t0 + 1.5), 3u);
  EXPECT_EQ(count(t0 + 2.0), 2u);  // current + bridge to the last point
  EXPECT_EQ(count(t0 + 3.0), 2u);
  EXPECT_EQ(count(t0 + 4.0), 0u);
  EXPECT_EQ(count(t0 + 5.0), 0u);
}

TEST_F(TrajectoryInit, SegmentValues) {
  const InitResult r = initJointTrajectory(command, command.stamp);
  ASSERT_EQ(r.trajectory.at(0).size(), 2u);
  for (std::size_t i = 0; i < 2; ++i) {
    const JointSegment& segment = r.trajectory[0][i];
    const TrajectoryPoint& a = command.points[i];
    const TrajectoryPoint& b = command.points[i + 1];
    EXPECT_EQ(segment.startTime(), command.stamp + a.time_from_start);
    EXPECT_EQ(segment.endTime(), command.stamp + b.time_from_start);
    EXPECT_EQ(segment.timeFromStart(), a.time_from_start);
    EXPECT_EQ(stateOf(segment, segment.startTime()).position[0], a.positions[0]);
    EXPECT_EQ(stateOf(segment, segment.endTime()).position[0], b.positions[0]);
    EXPECT_EQ(stateOf(segment, segment.endTime()).velocity[0], 0.0);
  }
}

TEST_F(TrajectoryInit, BridgeFromTheCurrentState) {
  InitOptions options;
  options.current_trajectory = &current;
  const InitResult r = initJointTrajectory(command, 0.0, options);
  ASSERT_EQ(r.trajectory.at(0).size(), 4u);
  EXPECT_EQ(r.trajectory[0][0].startTime(), current[0][0].startTime());
  EXPECT_EQ(r.trajectory[0][0].endTime(), current[0][0].endTime());
  const JointSegment& bridge = r.trajectory[0][1];
  EXPECT_EQ(bridge.startTime(), command.stamp);
  EXPECT_EQ(bridge.endTime(), command.stamp + command.points[0].time_from_start);
  const State ref = stateOf(current[0][0], command.stamp);
  const State start = stateOf(bridge, bridge.startTime());
  EXPECT_EQ(start.position[0], ref.position[0]);
  EXPECT_EQ(start.velocity[0], ref.velocity[0]);
  EXPECT_EQ(start.acceleration[0], ref.acceleration[0]);
  EXPECT_EQ(stateOf(bridge, bridge.endTime()).position[0], command.points[0].positions[0]);
  EXPECT_EQ(r.trajectory[0][2].startTime(), command.stamp + 1.0);
  EXPECT_EQ(r.trajectory[0][3].endTime(), command.stamp + 4.0);
}

// other_time_base: the current trajectory keeps its times, the new segments are shifted.
TEST_F(TrajectoryInit, OtherTimeBase) {
  InitOptions options;
  options.current_trajectory = &current;
  options.other_time_base = command.stamp + 1.0;
  const InitResult r = initJointTrajectory(command, command.stamp, options);
  ASSERT_EQ(r.trajectory.at(0).size(), 4u);
  EXPECT_EQ(r.trajectory[0][0].startTime(), current[0][0].startTime());
  EXPECT_EQ(r.trajectory[0][1].startTime(), command.stamp + 1.0);
  EXPECT_EQ(r.trajectory[0][1].endTime(), command.stamp + 1.0 + 1.0);
  EXPECT_EQ(r.trajectory[0][2].startTime(), command.stamp + 1.0 + 1.0);
  EXPECT_EQ(r.trajectory[0][3].endTime(), command.stamp + 4.0 + 1.0);
}

TEST_F(TrajectoryInit, JointsMappedByName) {
  for (std::size_t i = 0; i < 3; ++i) {
    command.points[i].positions.push_back(-command.points[i].positions[0]);
    command.points[i].velocities.push_back(0.0);
    command.points[i].accelerations.push_back(0.0);
  }
  command.joint_names.push_back("bar_joint");
  // No controller joints: the command's order.
  InitResult r = initJointTrajectory(command, command.stamp);
  ASSERT_EQ(r.trajectory.size(), 2u);
  EXPECT_EQ(stateOf(r.trajectory[0][0], 1.5).position[0], 2.0);
  EXPECT_EQ(stateOf(r.trajectory[1][0], 1.5).position[0], -2.0);
  // The controller's order, reversed.
  const std::vector<std::string> reversed = {"bar_joint", "foo_joint"};
  InitOptions options;
  options.joint_names = &reversed;
  r = initJointTrajectory(command, command.stamp, options);
  ASSERT_EQ(r.trajectory.size(), 2u);
  EXPECT_EQ(stateOf(r.trajectory[0][0], 1.5).position[0], -2.0);
  EXPECT_EQ(stateOf(r.trajectory[1][0], 1.5).position[0], 2.0);
  // Not the controller's joints: one too many, or one unknown.
  const char* expected = "Cannot create trajectory from message. It does not contain the expected joints.";
  const std::vector<std::string> only_foo = {"foo_joint"};
  options.joint_names = &only_foo;
  EXPECT_EQ(initJointTrajectory(command, command.stamp, options).error, expected);
  const std::vector<std::string> foo_baz = {"foo_joint", "baz_joint"};
  options.joint_names = &foo_baz;
  r = initJointTrajectory(command, command.stamp, options);
  EXPECT_TRUE(r.trajectory.empty());
  EXPECT_EQ(r.error, expected);
}

TEST_F(TrajectoryInit, PartialJointsGoal) {
  const std::vector<std::string> joints = {"bar_joint", "foo_joint"};
  Trajectory current2 = {current[0], current[0]};
  InitOptions options;
  options.joint_names = &joints;
  options.current_trajectory = &current2;
  options.goal = 7;
  // Not allowed: a command for foo_joint alone is refused.
  EXPECT_EQ(initJointTrajectory(command, 0.0, options).error,
            "Cannot create trajectory from message. It does not contain the expected joints.");
  options.allow_partial_joints_goal = true;
  const InitResult r = initJointTrajectory(command, 0.0, options);
  ASSERT_TRUE(r.ok()) << r.error;
  ASSERT_EQ(r.trajectory.size(), 2u);
  // bar_joint: the current trajectory unchanged, its segments from now on given to the goal.
  ASSERT_EQ(r.trajectory[0].size(), 2u);
  EXPECT_EQ(r.trajectory[0][1].endTime(), 10.0);
  EXPECT_EQ(r.trajectory[0][0].goal(), 7u);
  EXPECT_EQ(r.trajectory[0][1].goal(), 7u);
  // foo_joint: current + bridge + 2 new; the kept segment keeps its (no) goal.
  ASSERT_EQ(r.trajectory[1].size(), 4u);
  EXPECT_EQ(r.trajectory[1][0].goal(), 0u);
  for (std::size_t i = 1; i < 4; ++i) EXPECT_EQ(r.trajectory[1][i].goal(), 7u);
}

// A continuous joint's new positions are shifted by whole turns so the bridge takes the short way.
TEST_F(TrajectoryInit, WraparoundOffsets) {
  const double wrap = 4 * M_PI;
  for (TrajectoryPoint& p : command.points) p.positions[0] += wrap;
  const std::vector<bool> wraps = {true};
  InitOptions options;
  options.current_trajectory = &current;
  options.angle_wraparound = &wraps;
  const InitResult r = initJointTrajectory(command, 0.0, options);
  ASSERT_EQ(r.trajectory.at(0).size(), 4u);
  EXPECT_DOUBLE_EQ(stateOf(r.trajectory[0][1], r.trajectory[0][1].endTime()).position[0],
                   command.points[0].positions[0] - wrap);
  for (std::size_t i = 2; i < 4; ++i) {
    const JointSegment& segment = r.trajectory[0][i];
    EXPECT_DOUBLE_EQ(stateOf(segment, segment.startTime()).position[0],
                     command.points[i - 2].positions[0] - wrap);
    EXPECT_DOUBLE_EQ(stateOf(segment, segment.endTime()).position[0],
                     command.points[i - 1].positions[0] - wrap);
  }
  // A vector of the wrong size is refused.
  const std::vector<bool> two = {true, true};
  options.angle_wraparound = &two;
  EXPECT_EQ(initJointTrajectory(command, command.stamp, options).error,
            "Cannot create trajectory from message. Vector specifying whether joints wrap "
            "around has an invalid size.");
  // Without a current trajectory the vector is not used (a warning), positions unchanged.
  InitOptions no_current;
  no_current.angle_wraparound = &wraps;
  const InitResult plain = initJointTrajectory(command, 0.0, no_current);
  ASSERT_EQ(plain.trajectory.at(0).size(), 2u);
  EXPECT_EQ(stateOf(plain.trajectory[0][0], 0.0).position[0], command.points[0].positions[0]);
  ASSERT_EQ(plain.warnings.size(), 1u);
  EXPECT_EQ(plain.warnings[0],
            "Vector specifying whether joints wrap around will not be used because no current "
            "trajectory was given.");
}

TEST(TrajectoryWraparound, Offset) {
  EXPECT_EQ(wraparoundOffset(0.0, 4 * M_PI + 1.0, false), 0.0);
  EXPECT_NEAR(wraparoundOffset(0.0, 4 * M_PI + 1.0, true), -4 * M_PI, 1e-12);
  EXPECT_NEAR(wraparoundOffset(3.0, -3.0, true), 2 * M_PI, 1e-12);  // across +-pi
  // Exactly pi apart: towards where the next position lies (upstream's singularity rule).
  EXPECT_NEAR(wraparoundOffset(0.0, M_PI, true), 0.0, 1e-12);
  EXPECT_NEAR(wraparoundOffset(0.0, -M_PI, true), 0.0, 1e-12);
  EXPECT_NEAR(shortestAngularDistance(0.0, 3 * M_PI / 2), -M_PI / 2, 1e-12);
  EXPECT_NEAR(shortestAngularDistance(-M_PI, M_PI), 0.0, 1e-12);
}

TEST_F(TrajectoryInit, GoalTolerancesOverTheDefaults) {
  SegmentTolerances defaults(1);
  defaults.state_tolerance[0].position = 0.05;
  defaults.goal_state_tolerance[0].position = 0.03;
  defaults.goal_state_tolerance[0].velocity = 0.01;
  defaults.goal_time_tolerance = 1.0;
  GoalTolerances goal;
  goal.path_tolerance = {{"foo_joint", 0.2, -1.0, 0.0}};
  goal.goal_time_tolerance = 0.5;
  InitOptions options;
  options.current_trajectory = &current;
  options.default_tolerances = &defaults;
  options.goal_tolerances = &goal;
  options.goal = 3;
  const InitResult r = initJointTrajectory(command, 0.0, options);
  ASSERT_EQ(r.trajectory.at(0).size(), 4u);
  for (std::size_t i = 1; i < 4; ++i) {
    const SegmentTolerancesPerJoint& tol = r.trajectory[0][i].tolerances();
    EXPECT_EQ(tol.state_tolerance.position, 0.2);
    EXPECT_EQ(tol.state_tolerance.velocity, 0.0);
    EXPECT_EQ(tol.goal_state_tolerance.position, 0.03);
    EXPECT_EQ(tol.goal_state_tolerance.velocity, 0.01);
    EXPECT_EQ(tol.goal_time_tolerance, 0.5);
  }
  // A topic command (no goal): no tolerances on its segments.
  options.goal = 0;
  const InitResult topic = initJointTrajectory(command, 0.0, options);
  EXPECT_EQ(topic.trajectory.at(0)[2].tolerances().state_tolerance.position, 0.0);
}

TEST_F(TrajectoryInit, BadCommandsAreRefusedWithAReason) {
  auto error = [&](const JointTrajectoryCommand& c) { return initJointTrajectory(c, 0.0).error; };
  JointTrajectoryCommand c = command;
  c.points.clear();
  EXPECT_EQ(error(c), "Trajectory message contains empty trajectory. Nothing to convert.");
  c = command;
  c.points[1].time_from_start = 1.0;
  EXPECT_EQ(error(c),
            "Trajectory message contains waypoints that are not strictly increasing in time.");
  c = command;
  c.points[2].positions.push_back(0.0);  // upstream: std::invalid_argument
  EXPECT_EQ(error(c),
            "Invalid trajectory point at index: 2. Size mismatch in trajectory point position, "
            "velocity or acceleration data. (1 joint(s); 2 position(s), 1 velocit(ies), 1 "
            "acceleration(s))");
  c = command;
  c.points[0].positions.clear();
  EXPECT_NE(error(c).find("Invalid trajectory point at index: 0."), std::string::npos);
  c = command;
  c.points[1].velocities = {std::numeric_limits<double>::quiet_NaN()};
  EXPECT_EQ(error(c), "Invalid trajectory point at index: 1. It holds a non-finite value (nan or inf).");
  c = command;
  c.joint_names = {"foo_joint", "foo_joint"};
  for (TrajectoryPoint& p : c.points) {
    p.positions = {1.0, 1.0};
    p.velocities.clear();
    p.accelerations.clear();
  }
  EXPECT_EQ(error(c), "Cannot create trajectory from message. Joint 'foo_joint' is named twice.");
}

}  // namespace
