// joint_trajectory_controller's controller class over a simple two-joint arm whose dynamics
// the test integrates (position joints follow their command, velocity joints integrate it,
// effort joints are unit inertias): trajectories followed, goal outcomes, preemption, cancel,
// bad input.
#include <algorithm>
#include <cmath>
#include <limits>
#include <map>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "tianracer_control/controller_registry.h"
#include "tianracer_control/controller_set.h"
#include "tianracer_control/controllers/joint_trajectory_controller.h"

#include "control_test_support.h"

using namespace tianracer_control;  // NOLINT: test file
using trajectory::GoalTolerances;
using trajectory::JointTrajectoryCommand;
using trajectory::TrajectoryPoint;
using Event = JointTrajectoryController::GoalEvent;

namespace {

constexpr double kDt = 0.001;

struct Arm {
  JointHandle shoulder, elbow;
  std::map<std::string, JointHandle*> joints;
  ControllerSet set;
  JointTrajectoryController* jtc = nullptr;
  std::vector<Event> events;

  explicit Arm(JointHandle::Interface iface) {
    shoulder.name = "shoulder";
    elbow.name = "elbow";
    for (JointHandle* j : {&shoulder, &elbow}) {
      j->interface = iface;
      j->has_position_limits = true;
      j->lower = -2.0;
      j->upper = 2.0;
      joints[j->name] = j;
    }
  }
  static ControllerSpec spec(const std::string& type) {
    ControllerSpec s = test::spec("arm_controller", type, "");
    s.params["joints"] = ParamValue::list({ParamValue("shoulder"), ParamValue("elbow")});
    return s;
  }
  static void gains(ControllerSpec& s, double p, double d) {
    for (const char* j : {"shoulder", "elbow"}) {
      s.params["gains"][j]["p"] = p;
      s.params["gains"][j]["d"] = d;
    }
  }
  void load(const ControllerSpec& s) {
    jtc = &dynamic_cast<JointTrajectoryController&>(set.load(s, joints));
  }
  // One control period: the controller, then the arm's dynamics. A position joint stops at its
  // limits, as the hardware holds it (the controller passes the command on as it is).
  void step() {
    set.update(kDt);
    for (JointHandle* j : {&shoulder, &elbow}) {
      switch (j->interface) {
        case JointHandle::Interface::kPosition: {
          const double reached = std::clamp(j->command, j->lower, j->upper);
          j->velocity = (reached - j->position) / kDt;
          j->position = reached;
          break;
        }
        case JointHandle::Interface::kVelocity:
          j->velocity = j->command;
          j->position += j->velocity * kDt;
          break;
        case JointHandle::Interface::kEffort:
          j->velocity += j->command * kDt;
          j->position += j->velocity * kDt;
          break;
      }
    }
    for (const Event& e : jtc->takeGoalEvents()) events.push_back(e);
  }
  void run(double seconds) {
    const int n = static_cast<int>(std::lround(seconds / kDt));
    for (int i = 0; i < n; ++i) step();
  }
};

JointTrajectoryCommand twoPoints(double s1, double e1, double s2, double e2) {
  JointTrajectoryCommand c;
  c.joint_names = {"shoulder", "elbow"};
  TrajectoryPoint a, b;
  a.positions = {s1, e1};
  a.velocities = {0.0, 0.0};
  a.time_from_start = 1.0;
  b.positions = {s2, e2};
  b.velocities = {0.0, 0.0};
  b.time_from_start = 2.0;
  c.points = {a, b};
  return c;
}

std::string loadError(const ControllerSpec& s, std::map<std::string, JointHandle*>& joints) {
  try {
    builtinControllers().create(s, joints);
  } catch (const ControllerError& e) {
    return e.what();
  }
  return "";
}

}  // namespace

TEST(JointTrajectoryController, RegisteredForTheThreeInterfacesClaimingTheirJoints) {
  for (const char* type : {JointTrajectoryController::kPositionType,
                           JointTrajectoryController::kVelocityType,
                           JointTrajectoryController::kEffortType}) {
    EXPECT_TRUE(builtinControllers().has(type)) << type;
  }
  Arm arm(JointHandle::Interface::kVelocity);
  ControllerSpec s = Arm::spec(JointTrajectoryController::kVelocityType);
  Arm::gains(s, 10.0, 0.0);
  arm.load(s);
  ASSERT_EQ(arm.jtc->claimedJoints().size(), 2u);
  EXPECT_EQ(arm.jtc->claimedJoints()[1]->name, "elbow");
  // a position JTC cannot claim velocity joints
  EXPECT_NE(loadError(Arm::spec(JointTrajectoryController::kPositionType), arm.joints)
                .find("interface"),
            std::string::npos);
}

TEST(JointTrajectoryController, PositionJointsFollowTheSplineAndTheGoalSucceeds) {
  Arm arm(JointHandle::Interface::kPosition);
  arm.shoulder.position = 0.2;
  arm.load(Arm::spec(JointTrajectoryController::kPositionType));
  arm.run(0.1);
  EXPECT_DOUBLE_EQ(arm.shoulder.position, 0.2);  // held where it started

  const JointTrajectoryCommand c = twoPoints(1.0, -0.5, 1.5, 0.5);
  ASSERT_TRUE(arm.jtc->startGoal(7, c, GoalTolerances()).ok());
  EXPECT_EQ(arm.jtc->activeGoal(), 7u);
  const double start = arm.jtc->time() + kDt;  // the trajectory starts at the next update
  // cubic from (0.2, 0) to (1.0, 0) over 1 s: at the middle, the mean
  arm.run(0.501);  // the first update of the trajectory, then 500 more
  EXPECT_NEAR(arm.shoulder.position, 0.6, 1e-9);
  EXPECT_NEAR(arm.elbow.position, -0.25, 1e-9);
  // the query service samples the same trajectory, also ahead of time
  trajectory::State q;
  std::string error;
  ASSERT_TRUE(arm.jtc->queryState(start + 1.5, q, error)) << error;
  EXPECT_NEAR(q.position[0], 1.25, 1e-9);
  EXPECT_NEAR(q.velocity[0], 0.75, 1e-9);  // cubic 1.0 -> 1.5 in 1 s: 1.5 (dp/T) at the middle
  EXPECT_TRUE(arm.events.empty());
  arm.run(1.6);
  EXPECT_NEAR(arm.shoulder.position, 1.5, 1e-12);
  EXPECT_NEAR(arm.elbow.position, 0.5, 1e-12);
  ASSERT_EQ(arm.events.size(), 1u);
  EXPECT_EQ(arm.events[0].goal, 7u);
  EXPECT_EQ(arm.events[0].kind, Event::Kind::kSucceeded);
  EXPECT_EQ(arm.jtc->activeGoal(), 0u);
  // before the sim time the controller started at there is no trajectory
  EXPECT_FALSE(arm.jtc->queryState(-10.0, q, error));
  EXPECT_EQ(error, "Requested sample time precedes trajectory start time.");
}

TEST(JointTrajectoryController, EffortJointsTrackWithPidAndVelocityFeedForward) {
  Arm arm(JointHandle::Interface::kEffort);
  ControllerSpec s = Arm::spec(JointTrajectoryController::kEffortType);
  Arm::gains(s, 400.0, 40.0);
  arm.load(s);
  ASSERT_TRUE(arm.jtc->command(twoPoints(0.5, -0.5, 1.0, -1.0)).ok());
  arm.run(3.0);
  EXPECT_NEAR(arm.shoulder.position, 1.0, 1e-3);
  EXPECT_NEAR(arm.elbow.position, -1.0, 1e-3);
  EXPECT_NEAR(arm.jtc->stateError().position[0], 0.0, 1e-3);

  Arm vel(JointHandle::Interface::kVelocity);
  ControllerSpec v = Arm::spec(JointTrajectoryController::kVelocityType);
  Arm::gains(v, 0.0, 0.0);  // feed-forward only: the desired velocity integrated
  v.params["velocity_ff"]["shoulder"] = 1.0;
  v.params["velocity_ff"]["elbow"] = 1.0;
  vel.load(v);
  ASSERT_TRUE(vel.jtc->command(twoPoints(0.5, -0.5, 1.0, -1.0)).ok());
  vel.run(2.5);
  EXPECT_NEAR(vel.shoulder.position, 1.0, 2e-3);
  EXPECT_NEAR(vel.elbow.position, -1.0, 2e-3);
}

TEST(JointTrajectoryController, PathToleranceViolationAbortsTheGoal) {
  Arm arm(JointHandle::Interface::kEffort);
  ControllerSpec s = Arm::spec(JointTrajectoryController::kEffortType);
  Arm::gains(s, 1.0, 0.0);  // far too weak to follow
  s.params["constraints"]["elbow"]["trajectory"] = 0.05;
  arm.load(s);
  ASSERT_TRUE(arm.jtc->startGoal(3, twoPoints(0.0, 1.0, 0.0, 1.5), GoalTolerances()).ok());
  arm.run(2.0);
  ASSERT_EQ(arm.events.size(), 1u);
  EXPECT_EQ(arm.events[0].kind, Event::Kind::kAborted);
  EXPECT_EQ(arm.events[0].error_code, -4);
  EXPECT_EQ(arm.events[0].error_string.rfind("elbow path error 0.05", 0), 0u)
      << arm.events[0].error_string;
}

TEST(JointTrajectoryController, GoalToleranceViolationAbortsAfterGoalTime) {
  Arm arm(JointHandle::Interface::kPosition);
  ControllerSpec s = Arm::spec(JointTrajectoryController::kPositionType);
  s.params["constraints"]["goal_time"] = 0.2;
  s.params["constraints"]["shoulder"]["goal"] = 0.01;
  arm.load(s);
  // 2.5 rad is past the joint's upper limit (2): the command goes on as it is (upstream), the
  // joint stops at the limit, the goal is not reached
  ASSERT_TRUE(arm.jtc->startGoal(4, twoPoints(1.0, 0.0, 2.5, 0.0), GoalTolerances()).ok());
  arm.run(2.15);
  EXPECT_DOUBLE_EQ(arm.shoulder.command, 2.5);
  EXPECT_TRUE(arm.events.empty());  // within goal_time
  arm.run(0.1);
  ASSERT_EQ(arm.events.size(), 1u);
  EXPECT_EQ(arm.events[0].error_code, -5);
  EXPECT_EQ(arm.events[0].error_string, "shoulder goal error 0.500000");
  // the goal's own tolerances over the defaults: 0.6 rad passes
  GoalTolerances loose;
  loose.goal_tolerance.push_back({"shoulder", 0.6, 0.0, 0.0});
  ASSERT_TRUE(arm.jtc->startGoal(5, twoPoints(1.0, 0.0, 2.5, 0.0), loose).ok());
  arm.run(2.5);
  ASSERT_EQ(arm.events.size(), 2u);
  EXPECT_EQ(arm.events[1].kind, Event::Kind::kSucceeded);
}

TEST(JointTrajectoryController, ANewerGoalPreemptsACancelHolds) {
  Arm arm(JointHandle::Interface::kPosition);
  arm.load(Arm::spec(JointTrajectoryController::kPositionType));
  ASSERT_TRUE(arm.jtc->startGoal(1, twoPoints(1.0, 1.0, 1.5, 1.5), GoalTolerances()).ok());
  arm.run(0.5);
  ASSERT_TRUE(arm.jtc->startGoal(2, twoPoints(-1.0, -1.0, -1.5, -1.5), GoalTolerances()).ok());
  ASSERT_EQ(arm.events.size(), 0u);  // events come with the next step
  arm.step();
  ASSERT_EQ(arm.events.size(), 1u);
  EXPECT_EQ(arm.events[0].goal, 1u);
  EXPECT_EQ(arm.events[0].kind, Event::Kind::kCanceled);
  arm.run(0.5);
  EXPECT_FALSE(arm.jtc->cancelGoal(1));  // not the active one
  ASSERT_TRUE(arm.jtc->cancelGoal(2));
  const double held = arm.shoulder.position;
  arm.run(1.0);
  EXPECT_DOUBLE_EQ(arm.shoulder.position, held);
  ASSERT_EQ(arm.events.size(), 2u);
  EXPECT_EQ(arm.events[1].goal, 2u);
  EXPECT_EQ(arm.events[1].kind, Event::Kind::kCanceled);
  // a topic command preempts a goal as well
  ASSERT_TRUE(arm.jtc->startGoal(3, twoPoints(0.0, 0.0, 0.1, 0.1), GoalTolerances()).ok());
  ASSERT_TRUE(arm.jtc->command(twoPoints(0.3, 0.3, 0.4, 0.4)).ok());
  arm.step();
  ASSERT_EQ(arm.events.size(), 3u);
  EXPECT_EQ(arm.events[2].goal, 3u);
  EXPECT_EQ(arm.events[2].kind, Event::Kind::kCanceled);
}

TEST(JointTrajectoryController, StopTrajectoryDurationRampsToRestOnCancel) {
  Arm arm(JointHandle::Interface::kPosition);
  ControllerSpec s = Arm::spec(JointTrajectoryController::kPositionType);
  s.params["stop_trajectory_duration"] = 0.2;
  arm.load(s);
  ASSERT_TRUE(arm.jtc->startGoal(1, twoPoints(1.0, 1.0, 2.0, 2.0), GoalTolerances()).ok());
  arm.run(1.5);
  const double p = arm.jtc->desiredState().position[0];
  const double v = arm.jtc->desiredState().velocity[0];
  ASSERT_GT(v, 0.5);
  ASSERT_TRUE(arm.jtc->cancelGoal(1));
  arm.run(0.5);
  EXPECT_NEAR(arm.shoulder.position, p + 5.0 / 8.0 * v * 0.2, 1e-9);  // stopTrajectory's rest
  EXPECT_NEAR(arm.jtc->desiredState().velocity[0], 0.0, 1e-12);
}

TEST(JointTrajectoryController, BadGoalsAreRejectedAndNothingChanges) {
  Arm arm(JointHandle::Interface::kPosition);
  arm.load(Arm::spec(JointTrajectoryController::kPositionType));
  ASSERT_TRUE(arm.jtc->startGoal(1, twoPoints(1.0, 1.0, 1.5, 1.5), GoalTolerances()).ok());
  arm.run(0.2);
  const double before = arm.shoulder.position;

  JointTrajectoryCommand nan = twoPoints(0.0, std::numeric_limits<double>::quiet_NaN(), 0.0, 0.0);
  auto r = arm.jtc->startGoal(2, nan, GoalTolerances());
  EXPECT_FALSE(r.ok());
  EXPECT_EQ(r.error_code, -1);  // INVALID_GOAL
  EXPECT_NE(r.error.find("non-finite"), std::string::npos) << r.error;

  JointTrajectoryCommand wrong = twoPoints(0.0, 0.0, 0.0, 0.0);
  wrong.joint_names = {"shoulder", "wrist"};
  r = arm.jtc->startGoal(3, wrong, GoalTolerances());
  EXPECT_EQ(r.error_code, -2);  // INVALID_JOINTS
  EXPECT_EQ(r.error, "Joints on incoming goal don't match the controller joints.");
  wrong.joint_names = {"shoulder"};
  wrong.points[0].positions.resize(1);
  wrong.points[1].positions.resize(1);
  wrong.points[0].velocities.resize(1);
  wrong.points[1].velocities.resize(1);
  EXPECT_EQ(arm.jtc->startGoal(4, wrong, GoalTolerances()).error_code, -2);  // partial: not allowed

  JointTrajectoryCommand backwards = twoPoints(0.0, 0.0, 0.0, 0.0);
  backwards.points[1].time_from_start = 0.5;
  r = arm.jtc->startGoal(5, backwards, GoalTolerances());
  EXPECT_EQ(r.error_code, -1);
  EXPECT_FALSE(arm.jtc->command(backwards).ok());

  // goal 1 goes on untouched
  EXPECT_EQ(arm.jtc->activeGoal(), 1u);
  arm.run(2.0);
  EXPECT_GT(arm.shoulder.position, before);
  EXPECT_NEAR(arm.shoulder.position, 1.5, 1e-12);
  ASSERT_EQ(arm.events.size(), 1u);
  EXPECT_EQ(arm.events[0].kind, Event::Kind::kSucceeded);
}

TEST(JointTrajectoryController, PartialGoalsWhenAllowed) {
  Arm arm(JointHandle::Interface::kPosition);
  ControllerSpec s = Arm::spec(JointTrajectoryController::kPositionType);
  s.params["allow_partial_joints_goal"] = true;
  arm.elbow.position = 0.3;
  arm.load(s);
  JointTrajectoryCommand c;
  c.joint_names = {"shoulder"};
  TrajectoryPoint p;
  p.positions = {0.8};
  p.velocities = {0.0};  // comes to rest (the goal's velocity tolerance, 0.01 by default)
  p.time_from_start = 1.0;
  c.points = {p};
  ASSERT_TRUE(arm.jtc->startGoal(1, c, GoalTolerances()).ok());
  arm.run(1.5);
  EXPECT_NEAR(arm.shoulder.position, 0.8, 1e-12);
  EXPECT_DOUBLE_EQ(arm.elbow.position, 0.3);
  ASSERT_EQ(arm.events.size(), 1u);
  EXPECT_EQ(arm.events[0].kind, Event::Kind::kSucceeded) << arm.events[0].error_string;
}

TEST(JointTrajectoryController, BadParametersFailTheLoadWithUpstreamsMessage) {
  Arm arm(JointHandle::Interface::kEffort);
  ControllerSpec s = test::spec("arm_controller", JointTrajectoryController::kEffortType, "");
  EXPECT_NE(loadError(s, arm.joints).find("Could not find 'joints' parameter"), std::string::npos);
  s.params["joints"] = "shoulder";
  EXPECT_NE(loadError(s, arm.joints).find("The 'joints' parameter is not an array"),
            std::string::npos);
  s.params["joints"] = ParamValue::list({ParamValue("shoulder"), ParamValue(3)});
  EXPECT_NE(loadError(s, arm.joints).find("contains a non-string element"), std::string::npos);
  s.params["joints"] = ParamValue::list({ParamValue("shoulder"), ParamValue("wrist")});
  EXPECT_NE(loadError(s, arm.joints).find("wrist"), std::string::npos);
  s = Arm::spec(JointTrajectoryController::kEffortType);
  EXPECT_NE(loadError(s, arm.joints).find("Failed to initialize PID gains"), std::string::npos);
  Arm::gains(s, 1.0, 0.0);
  EXPECT_EQ(loadError(s, arm.joints), "");
  s.params["gains"]["elbow"]["p"] = "stiff";
  EXPECT_NE(loadError(s, arm.joints).find("gains/elbow/p"), std::string::npos);
  s = Arm::spec(JointTrajectoryController::kEffortType);
  Arm::gains(s, 1.0, 0.0);
  s.params["state_publish_rate"] = -5.0;
  EXPECT_NE(loadError(s, arm.joints).find("state_publish_rate"), std::string::npos);
  s.params["state_publish_rate"] = 50.0;
  s.params["velocity_ff"]["elbow"] = "fast";
  EXPECT_NE(loadError(s, arm.joints).find("velocity_ff/elbow"), std::string::npos);
}

TEST(JointTrajectoryController, StateIsDueAtStatePublishRate) {
  Arm arm(JointHandle::Interface::kPosition);
  ControllerSpec s = Arm::spec(JointTrajectoryController::kPositionType);
  s.params["state_publish_rate"] = 25.0;
  arm.load(s);
  int due = 0;
  for (int i = 0; i < 1000; ++i) {
    arm.step();
    if (arm.jtc->takeStateDue()) ++due;
  }
  // strictly after each 40 ms of uptime (upstream's `<`): 24 in 1 s, or 25 when the sum of
  // the periods rounds above 0.04 s at the 40th update (upstream sums exact nanoseconds)
  EXPECT_GE(due, 24);
  EXPECT_LE(due, 25);
}
