// gripper_action_controller over one finger joint whose dynamics the test integrates (a position
// joint follows its command; an effort joint is a 0.1 kg slider that an object can block):
// reached goals, stalls, max_effort, preemption, cancel, bad input.
#include <cmath>
#include <limits>
#include <map>
#include <optional>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "tianracer_control/controller_registry.h"
#include "tianracer_control/controller_set.h"
#include "tianracer_control/controllers/gripper_action_controller.h"

#include "control_test_support.h"

using namespace tianracer_control;  // NOLINT: test file
using Event = GripperActionController::GoalEvent;

namespace {

constexpr double kDt = 0.001;

struct Gripper {
  JointHandle finger;
  std::map<std::string, JointHandle*> joints;
  ControllerSet set;
  GripperActionController* gac = nullptr;
  std::vector<Event> events;
  std::optional<double> blocked_at;  // an object: the finger stops there when closing
  double max_command = 0.0;

  explicit Gripper(JointHandle::Interface iface) {
    finger.name = "finger_joint";
    finger.interface = iface;
    finger.has_position_limits = true;
    finger.lower = 0.0;
    finger.upper = 0.08;
    finger.position = 0.08;  // open
    joints[finger.name] = &finger;
  }
  static ControllerSpec spec(const std::string& type) {
    ControllerSpec s = test::spec("gripper_controller", type, "finger_joint");
    if (type == GripperActionController::kEffortType) {
      s.params["gains"]["finger_joint"]["p"] = 200.0;
      s.params["gains"]["finger_joint"]["d"] = 10.0;
    }
    return s;
  }
  void load(const ControllerSpec& s) {
    gac = &dynamic_cast<GripperActionController&>(set.load(s, joints));
  }
  void step() {
    set.update(kDt);
    const double before = finger.position;
    if (finger.interface == JointHandle::Interface::kPosition) {
      finger.position = finger.command;
    } else {
      max_command = std::max(max_command, std::fabs(finger.command));
      finger.velocity += finger.command / 0.1 * kDt;
      finger.position += finger.velocity * kDt;
    }
    if (blocked_at && finger.position < *blocked_at) finger.position = *blocked_at;
    finger.velocity = (finger.position - before) / kDt;
    for (const Event& e : gac->takeGoalEvents()) events.push_back(e);
  }
  void run(double seconds) {
    const int n = static_cast<int>(std::lround(seconds / kDt));
    for (int i = 0; i < n; ++i) step();
  }
};

std::string loadError(const ControllerSpec& s, std::map<std::string, JointHandle*>& joints) {
  try {
    builtinControllers().create(s, joints);
  } catch (const ControllerError& e) {
    return e.what();
  }
  return "";
}

}  // namespace

TEST(GripperActionController, PositionFormReachesTheGoal) {
  Gripper g(JointHandle::Interface::kPosition);
  g.load(Gripper::spec(GripperActionController::kPositionType));
  EXPECT_EQ(g.gac->options().goal_tolerance, 0.01);  // upstream's defaults
  EXPECT_EQ(g.gac->options().stall_velocity_threshold, 0.001);
  EXPECT_EQ(g.gac->options().stall_timeout, 1.0);
  g.run(0.1);
  EXPECT_DOUBLE_EQ(g.finger.position, 0.08);  // holds where it started
  ASSERT_EQ(g.gac->startGoal(1, 0.03, 5.0), "");
  g.run(0.01);
  EXPECT_DOUBLE_EQ(g.finger.position, 0.03);
  ASSERT_EQ(g.events.size(), 1u);
  EXPECT_EQ(g.events[0].kind, Event::Kind::kSucceeded);
  EXPECT_TRUE(g.events[0].reached_goal);
  EXPECT_FALSE(g.events[0].stalled);
  EXPECT_DOUBLE_EQ(g.events[0].position, 0.03);
  EXPECT_DOUBLE_EQ(g.events[0].effort, 5.0);  // the position adapter reports max_effort
}

TEST(GripperActionController, EffortFormStallsOnAnObjectWithinMaxEffort) {
  Gripper g(JointHandle::Interface::kEffort);
  ControllerSpec s = Gripper::spec(GripperActionController::kEffortType);
  s.params["stall_timeout"] = 0.2;
  s.params["stall_velocity_threshold"] = 0.001;
  g.load(s);
  g.blocked_at = 0.02;  // the object
  ASSERT_EQ(g.gac->startGoal(1, 0.0, 3.0), "");
  g.run(0.1);  // at the object after ~0.065 s (30 m/s^2): pressing for < 0.2 s
  EXPECT_TRUE(g.events.empty());
  EXPECT_DOUBLE_EQ(g.finger.position, 0.02);
  g.run(1.0);
  ASSERT_EQ(g.events.size(), 1u);
  EXPECT_EQ(g.events[0].kind, Event::Kind::kAborted);
  EXPECT_TRUE(g.events[0].stalled);
  EXPECT_FALSE(g.events[0].reached_goal);
  EXPECT_DOUBLE_EQ(g.events[0].position, 0.02);
  EXPECT_DOUBLE_EQ(std::fabs(g.events[0].effort), 3.0);  // the PID saturated at max_effort
  EXPECT_LE(g.max_command, 3.0);

  // without an object it gets there
  g.blocked_at.reset();
  ASSERT_EQ(g.gac->startGoal(2, 0.005, 3.0), "");
  g.run(2.0);
  ASSERT_EQ(g.events.size(), 2u);
  EXPECT_EQ(g.events[1].kind, Event::Kind::kSucceeded);
  EXPECT_NEAR(g.events[1].position, 0.005, 0.01);
}

TEST(GripperActionController, ANewerGoalPreemptsACancelHolds) {
  Gripper g(JointHandle::Interface::kEffort);
  g.load(Gripper::spec(GripperActionController::kEffortType));
  ASSERT_EQ(g.gac->startGoal(1, 0.0, 0.1), "");  // 1 m/s^2: far from there in 0.2 s
  g.run(0.05);
  ASSERT_EQ(g.gac->startGoal(2, 0.0, 0.1), "");
  g.step();
  ASSERT_EQ(g.events.size(), 1u);
  EXPECT_EQ(g.events[0].goal, 1u);
  EXPECT_EQ(g.events[0].kind, Event::Kind::kCanceled);
  EXPECT_FALSE(g.gac->cancelGoal(1));
  g.run(0.1);
  ASSERT_TRUE(g.gac->cancelGoal(2));
  const double at = g.finger.position;
  EXPECT_DOUBLE_EQ(g.gac->command(), at);       // setHoldPosition: where it is
  EXPECT_DOUBLE_EQ(g.gac->maxEffort(), 0.0);    // at the default max_effort
  g.step();
  ASSERT_EQ(g.events.size(), 2u);
  EXPECT_EQ(g.events[1].kind, Event::Kind::kCanceled);
}

TEST(GripperActionController, BadInputFailsTheLoadOrRejectsTheGoal) {
  Gripper g(JointHandle::Interface::kEffort);
  ControllerSpec s = test::spec("gripper_controller", GripperActionController::kEffortType, "");
  EXPECT_NE(loadError(s, g.joints).find("Could not find joint name on param server"),
            std::string::npos);
  s.params["joint"] = "thumb_joint";
  EXPECT_NE(loadError(s, g.joints).find("thumb_joint"), std::string::npos);
  s = Gripper::spec(GripperActionController::kEffortType);
  s.params.erase("gains");
  EXPECT_NE(loadError(s, g.joints).find("Failed to initialize PID gains"), std::string::npos);
  s = Gripper::spec(GripperActionController::kEffortType);
  s.params["goal_tolerance"] = "tight";
  EXPECT_NE(loadError(s, g.joints).find("goal_tolerance"), std::string::npos);
  s.params["goal_tolerance"] = std::numeric_limits<double>::infinity();
  EXPECT_NE(loadError(s, g.joints).find("goal_tolerance"), std::string::npos);
  s.params["goal_tolerance"] = -0.02;  // upstream takes |value|
  s.params["action_monitor_rate"] = 0.0;
  EXPECT_NE(loadError(s, g.joints).find("action_monitor_rate"), std::string::npos);
  s.params.erase("action_monitor_rate");
  EXPECT_EQ(loadError(s, g.joints), "");
  // a position form cannot claim an effort joint
  EXPECT_NE(loadError(Gripper::spec(GripperActionController::kPositionType), g.joints)
                .find("interface"),
            std::string::npos);

  g.load(Gripper::spec(GripperActionController::kEffortType));
  ASSERT_EQ(g.gac->startGoal(1, 0.04, 2.0), "");
  g.run(0.05);
  EXPECT_NE(g.gac->startGoal(2, std::nan(""), 2.0).find("non-finite"), std::string::npos);
  EXPECT_EQ(g.gac->activeGoal(), 1u);  // goal 1 goes on
  g.run(2.0);
  ASSERT_EQ(g.events.size(), 1u);
  EXPECT_EQ(g.events[0].kind, Event::Kind::kSucceeded);
}
