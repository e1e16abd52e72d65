// The hold and stop trajectories (hold_trajectory_builder.h, stop_trajectory_builder.h, with the
// numbers of ros_controllers' stop_trajectory_builder_test.cpp), the state error, and the goal
// checks of the update loop (tolerance violations abort, all joints within the goal succeed).
#include <cmath>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "tianracer_control/trajectory/joint_trajectory.h"

using namespace tianracer_control::trajectory;  // NOLINT: test file

namespace {

constexpr double kEps = 1e-9;

State sampleAt(const JointSegment& segment, double t) {
  State s;
  segment.sample(t, s);
  return s;
}

TEST(TrajectoryHold, HoldsThePositionsFromNow) {
  const Trajectory hold = holdTrajectory(2.5, {0.3, -1.2}, 9);
  ASSERT_EQ(hold.size(), 2u);
  for (std::size_t i = 0; i < 2; ++i) {
    ASSERT_EQ(hold[i].size(), 1u);
    EXPECT_EQ(hold[i][0].startTime(), 2.5);
    EXPECT_EQ(hold[i][0].endTime(), 2.5);
    EXPECT_EQ(hold[i][0].goal(), 9u);
    for (double t : {2.5, 3.0, 100.0}) {
      const State s = sampleAt(hold[i][0], t);
      EXPECT_EQ(s.position[0], i == 0 ? 0.3 : -1.2);
      EXPECT_EQ(s.velocity[0], 0.0);
      EXPECT_EQ(s.acceleration[0], 0.0);
    }
  }
}

// Upstream's testBuildSuccess: two joints at 0.9 rad / -0.03 rad/s and 1.68 rad / 3.7 rad/s,
// stopped in 0.2 s from t = 0.11 s.
TEST(TrajectoryHold, StopTrajectoryComesToRestInTheDuration) {
  State desired(2);
  desired.position = {0.9, 1.68};
  desired.velocity = {-0.03, 3.7};
  const double start = 0.11, duration = 0.2;
  const Trajectory stop = stopTrajectory(start, duration, desired, 4);
  ASSERT_EQ(stop.size(), 2u);
  for (std::size_t i = 0; i < 2; ++i) {
    ASSERT_EQ(stop[i].size(), 1u);
    const JointSegment& segment = stop[i][0];
    EXPECT_NEAR(segment.startTime(), start, kEps);
    EXPECT_NEAR(segment.endTime(), start + duration, kEps);
    EXPECT_EQ(segment.goal(), 4u);
    const State s0 = sampleAt(segment, start);
    EXPECT_NEAR(s0.position[0], desired.position[i], kEps);
    EXPECT_NEAR(s0.velocity[0], desired.velocity[i], kEps);
    const State s1 = sampleAt(segment, start + duration);
    EXPECT_NEAR(s1.velocity[0], 0.0, kEps);
    // The mirrored quintic over D = 2T is p + v s - 2v s^3/D^2 + v s^4/D^3: at s = T it is at
    // p + 5/8 v T with velocity 0 and acceleration -3v/D; the segment ends in that state.
    EXPECT_NEAR(s1.position[0], desired.position[i] + 0.625 * desired.velocity[i] * duration,
                1e-12);
    EXPECT_NEAR(s1.acceleration[0], -1.5 * desired.velocity[i] / duration, 1e-9);
    // Monotonic: the joint never moves back while it slows down.
    double last = s0.position[0];
    for (int k = 1; k <= 20; ++k) {
      const double p = sampleAt(segment, start + duration * k / 20.0).position[0];
      EXPECT_GE((p - last) * desired.velocity[i], -1e-15) << k;
      last = p;
    }
  }
  EXPECT_THROW(stopTrajectory(start, 0.0, desired), std::invalid_argument);
  EXPECT_THROW(stopTrajectory(start, -1.0, desired), std::invalid_argument);
}

TEST(TrajectoryHold, StateErrorWrapsThePositionAsUpstream) {
  State desired(2), actual(2);
  desired.position = {0.1, 3.0};
  actual.position = {0.0, -3.0};
  desired.velocity = {1.0, 0.0};
  actual.velocity = {0.25, 0.5};
  const State e = stateError(desired, actual);
  EXPECT_NEAR(e.position[0], 0.1, 1e-12);
  EXPECT_NEAR(e.position[1], 6.0 - 2 * M_PI, 1e-12);  // the short way round
  EXPECT_EQ(e.velocity[0], 0.75);
  EXPECT_EQ(e.velocity[1], -0.5);
  EXPECT_EQ(e.acceleration[0], 0.0);
}

// One joint, a goal with a path tolerance of 0.1 and a goal tolerance of 0.05 reached within
// 0.5 s after its end at t = 2 s.
class GoalChecks : public ::testing::Test {
 protected:
  GoalChecks() {
    State s0(1), s1(1);
    s1.position[0] = 1.0;
    JointSegment segment(1.0, s0, 2.0, s1);
    segment.setGoal(5);
    SegmentTolerancesPerJoint tol;
    tol.state_tolerance.position = 0.1;
    tol.goal_state_tolerance.position = 0.05;
    tol.goal_time_tolerance = 0.5;
    segment.setTolerances(tol);
    trajectory = {{segment}};
  }

  GoalCheck check(double t, double position_error) {
    State e(1);
    e.position[0] = position_error;
    return checkGoal(trajectory, t, e, 5, names, done);
  }

  Trajectory trajectory;
  std::vector<std::string> names = {"foo_joint"};
  std::vector<bool> done;
};

TEST_F(GoalChecks, RunningThenSucceeded) {
  EXPECT_EQ(check(1.5, 0.09).outcome, GoalCheck::Outcome::kRunning);
  EXPECT_EQ(check(2.0, 0.2).outcome, GoalCheck::Outcome::kRunning);  // goal time left
  const GoalCheck ok = check(2.3, 0.04);
  EXPECT_EQ(ok.outcome, GoalCheck::Outcome::kSucceeded);
  EXPECT_EQ(ok.error_code, 0);
}

TEST_F(GoalChecks, PathToleranceAborts) {
  const GoalCheck c = check(1.5, -0.11);
  EXPECT_EQ(c.outcome, GoalCheck::Outcome::kPathToleranceViolated);
  EXPECT_EQ(c.error_code, -4);
  EXPECT_EQ(c.error_string, "foo_joint path error -0.110000");
}

TEST_F(GoalChecks, GoalToleranceAbortsAfterTheGoalTime) {
  EXPECT_EQ(check(2.49, 0.06).outcome, GoalCheck::Outcome::kRunning);
  const GoalCheck c = check(2.5, 0.06);
  EXPECT_EQ(c.outcome, GoalCheck::Outcome::kGoalToleranceViolated);
  EXPECT_EQ(c.error_code, -5);
  EXPECT_EQ(c.error_string, "foo_joint goal error 0.060000");
}

TEST_F(GoalChecks, OtherGoalsAndNoGoalAreNotChecked) {
  State e(1);
  e.position[0] = 10.0;
  EXPECT_EQ(checkGoal(trajectory, 1.5, e, 6, names, done).outcome, GoalCheck::Outcome::kRunning);
  EXPECT_EQ(checkGoal(trajectory, 1.5, e, 0, names, done).outcome, GoalCheck::Outcome::kRunning);
  EXPECT_EQ(checkGoal(trajectory, 0.5, e, 5, names, done).outcome,  // before the trajectory
            GoalCheck::Outcome::kRunning);
}

// Two joints: success only once both are within their goal tolerance (flags kept across calls).
TEST_F(GoalChecks, AllJointsMustBeDone) {
  trajectory.push_back(trajectory[0]);
  SegmentTolerancesPerJoint loose = trajectory[1][0].tolerances();
  loose.goal_time_tolerance = 10.0;
  trajectory[1][0].setTolerances(loose);
  names.push_back("bar_joint");
  State e(2);
  e.position = {0.0, 0.3};
  EXPECT_EQ(checkGoal(trajectory, 2.1, e, 5, names, done).outcome, GoalCheck::Outcome::kRunning);
  EXPECT_EQ(done, std::vector<bool>({true, false}));
  e.position = {0.3, 0.0};  // joint 0's flag stays while it has goal time left
  EXPECT_EQ(checkGoal(trajectory, 2.2, e, 5, names, done).outcome, GoalCheck::Outcome::kSucceeded);
  EXPECT_EQ(done, std::vector<bool>({false, false}));
}

}  // namespace
