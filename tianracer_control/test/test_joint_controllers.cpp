// Controllers and their registry: behaviour of each type and every configuration error.
#include <cmath>
#include <limits>
#include <map>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "tianracer_control/controllers/effort_joint_position_controller.h"
#include "tianracer_control/controllers/pid_state.h"
#include "tianracer_control/joint_controllers.h"

#include "control_test_support.h"

using namespace tianracer_control;  // NOLINT: test file

namespace {

using test::spec;

constexpr double kNan = std::numeric_limits<double>::quiet_NaN();
constexpr double kInf = std::numeric_limits<double>::infinity();

// The seed's actuated joints, the rear wheels with limits, and a position joint; and the
// controllers loaded on them.
struct Car : test::SeedJoints {
  JointHandle pos_joint;
  ControllerSet controllers;

  Car() {
    for (JointHandle* h : {&left_rear, &right_rear}) {
      h->velocity_limit = 100.0;
      h->effort_limit = 5.0;
    }
    pos_joint.interface = JointHandle::Interface::kPosition;
    pos_joint.has_position_limits = true;
    pos_joint.lower = -1.0;
    pos_joint.upper = 2.0;
    pos_joint.name = "pos_joint";
    joints[pos_joint.name] = &pos_joint;
  }
  Controller& load(const ControllerSpec& s) { return controllers.load(s, joints); }
  void update(double dt) { controllers.update(dt); }
};

ControllerSpec hingeSpec(double p, double i = 0.0, double d = 0.0) {
  ControllerSpec s = spec("hinge", "effort_controllers/JointPositionController",
                          "left_steering_hinge_joint");
  s.params["pid"]["p"] = p;
  s.params["pid"]["i"] = i;
  s.params["pid"]["d"] = d;
  return s;
}

std::unique_ptr<Controller> create(const ControllerSpec& s,
                                   std::map<std::string, JointHandle*>& joints,
                                   const WarningSink& warn = WarningSink()) {
  return builtinControllers().create(s, joints, warn);
}

// Builds the controller and returns the error text ("" if it did not throw).
std::string errorOf(const ControllerSpec& s, std::map<std::string, JointHandle*>& joints) {
  try {
    create(s, joints);
  } catch (const ControllerError& e) {
    return e.what();
  }
  return "";
}

bool startsWith(const std::string& s, const std::string& prefix) {
  return s.compare(0, prefix.size(), prefix) == 0;
}

}  // namespace

TEST(ShortestAngularDistance, Wraps) {
  EXPECT_NEAR(shortestAngularDistance(0.0, 1.0), 1.0, 1e-15);
  EXPECT_NEAR(shortestAngularDistance(3.0, -3.0), 2.0 * M_PI - 6.0, 1e-12);
  EXPECT_NEAR(shortestAngularDistance(-3.0, 3.0), 6.0 - 2.0 * M_PI, 1e-12);
  EXPECT_NEAR(shortestAngularDistance(0.0, 4.0 * M_PI + 0.5), 0.5, 1e-12);
}

// effort_controllers' update(): computeCommand(error, period), so the derivative is the change
// of the error between updates: a step of the target kicks the D term for one update, as in
// Gazebo; while the target holds it is -velocity's finite difference.
TEST(EffortJointPositionController, PidOnPositionErrorWithTheErrorsChangeAsDerivative) {
  Car car;
  car.left_hinge.position = 0.1;
  auto& c = car.load(hingeSpec(2.0, 0.0, 0.001));
  // starting(): target = current position, so nothing moves.
  EXPECT_EQ(c.command(), 0.1);
  car.update(0.001);
  EXPECT_EQ(car.left_hinge.command, 0.0);

  ASSERT_TRUE(c.setCommand(0.5));
  car.update(0.001);
  // error 0.4 (was 0): P = 0.8, D = 0.001 * 0.4 / 0.001 = 0.4: the kick
  EXPECT_NEAR(car.left_hinge.command, 1.2, 1e-9);

  car.left_hinge.position = 0.11;  // moved 0.01 in the update
  car.update(0.001);
  // error 0.39: P = 0.78, D = 0.001 * (0.39 - 0.4) / 0.001 = -0.01
  EXPECT_NEAR(car.left_hinge.command, 0.77, 1e-9);
}

// Upstream's enforceJointLimits clamps the target to the URDF position limits; the effort goes
// to the joint as the PID gives it (the hardware saturates it).
TEST(EffortJointPositionController, ClampsTargetToLimitsAndPassesTheEffortOn) {
  Car car;
  auto& c = car.load(hingeSpec(2.0));
  ASSERT_TRUE(c.setCommand(5.0));
  EXPECT_EQ(c.command(), 0.6);
  car.update(0.001);
  EXPECT_NEAR(car.left_hinge.command, 1.2, 1e-12);
  ASSERT_TRUE(c.setCommand(-1e9));
  EXPECT_EQ(c.command(), -0.6);

  Car strong;
  auto& s = strong.load(hingeSpec(100.0));
  s.setCommand(0.5);
  strong.update(0.001);
  EXPECT_EQ(strong.left_hinge.command, 50.0);  // not clamped to the 10 N m effort limit here
}

TEST(EffortJointPositionController, RejectsNonFiniteCommands) {
  Car car;
  auto& c = car.load(hingeSpec(1.0));
  ASSERT_TRUE(c.setCommand(0.3));
  EXPECT_FALSE(c.setCommand(kNan));
  EXPECT_FALSE(c.setCommand(kInf));
  EXPECT_FALSE(c.setCommand(-kInf));
  EXPECT_EQ(c.command(), 0.3);
}

TEST(EffortJointPositionController, ContinuousJointTakesTheShortWayRound) {
  Car car;
  car.left_rear.interface = JointHandle::Interface::kEffort;
  car.left_rear.position = 3.0;
  ControllerSpec s = spec("wheel", "effort_controllers/JointPositionController",
                          "left_rear_wheel_joint");
  s.params["pid"]["p"] = 1.0;
  auto& c = car.load(s);
  c.setCommand(-3.0);
  car.update(0.01);
  EXPECT_NEAR(car.left_rear.command, 2.0 * M_PI - 6.0, 1e-12);  // +0.283, not -6
}

TEST(EffortJointVelocityController, PidOnVelocityError) {
  Car car;
  car.left_rear.interface = JointHandle::Interface::kEffort;
  car.left_rear.velocity_limit = 5.0;
  car.left_rear.effort_limit = 100.0;
  ControllerSpec s = spec("v", "effort_controllers/JointVelocityController", "left_rear_wheel_joint");
  s.params["pid"]["p"] = 1;  // an int, as YAML gives "p: 1"
  s.params["pid"]["d"] = 0.01;
  auto& c = car.load(s);
  EXPECT_EQ(c.command(), 0.0);
  c.setCommand(10.0);
  EXPECT_EQ(c.command(), 10.0);  // not clamped to the velocity limit, as upstream
  car.left_rear.velocity = 1.0;
  car.update(0.01);
  EXPECT_NEAR(car.left_rear.command, 9.0, 1e-12);  // P = 9, D = 0 (first update)
  car.left_rear.velocity = 2.0;
  car.update(0.01);
  // P = 8, D = 0.01 * (8 - 9) / 0.01 = -1
  EXPECT_NEAR(car.left_rear.command, 7.0, 1e-12);
}

TEST(PidControllers, StateIsSampledOnEveryTenthUpdateWithTheUnclampedOutput) {
  // effort_controllers' joint_position_controller.cpp: loop_count_ % 10 == 0, then
  // loop_count_++: updates 0, 10, 20, ... since the controller was made; the command before the
  // hardware's effort limit; getGains' i_clamp (i_clamp_max) and antiwindup.
  Car car;
  ControllerSpec spec_ = hingeSpec(100.0, 1.0, 0.0);
  spec_.params["pid"]["i_clamp"] = 0.5;
  auto& c = car.load(spec_);
  const auto* source = dynamic_cast<const PidStateSource*>(&c);
  ASSERT_NE(source, nullptr);
  EXPECT_EQ(source->pidState().seq, 0u);
  car.left_hinge.position = 0.1;
  car.left_hinge.velocity = 0.25;
  ASSERT_TRUE(c.setCommand(0.3));
  car.update(0.002);  // update 0: sampled
  const PidStateSample& s = source->pidState();
  EXPECT_EQ(s.seq, 1u);
  EXPECT_DOUBLE_EQ(s.set_point, 0.3);
  EXPECT_DOUBLE_EQ(s.process_value, 0.1);
  EXPECT_DOUBLE_EQ(s.process_value_dot, 0.25);
  EXPECT_DOUBLE_EQ(s.error, 0.2);
  EXPECT_DOUBLE_EQ(s.time_step, 0.002);
  EXPECT_GT(s.command, 10.0);                  // P alone is 20 N m, above the effort limit:
  EXPECT_EQ(car.left_hinge.command, s.command);  // the hardware saturates it, not the controller
  EXPECT_EQ(s.gains.p, 100.0);
  EXPECT_EQ(s.gains.i_clamp_max, 0.5);
  for (int k = 1; k <= 9; ++k) car.update(0.002);
  EXPECT_EQ(source->pidState().seq, 1u);  // updates 1..9: none
  car.update(0.002);
  EXPECT_EQ(source->pidState().seq, 2u);  // update 10
  c.starting(0.0);  // a restart does not reset the count
  for (int k = 11; k <= 20; ++k) car.update(0.002);
  EXPECT_EQ(source->pidState().seq, 3u);  // update 20

  // effort_controllers/JointVelocityController: the velocity is the process value, its
  // derivative left 0 as upstream leaves it; velocity_controllers/JointPositionController.
  Car v;
  v.left_rear.interface = JointHandle::Interface::kEffort;
  ControllerSpec vs = spec("v", "effort_controllers/JointVelocityController", "left_rear_wheel_joint");
  vs.params["pid"]["p"] = 2.0;
  auto& vc = v.load(vs);
  vc.setCommand(3.0);
  v.left_rear.velocity = 1.0;
  v.update(0.01);
  const PidStateSample& vsample = dynamic_cast<const PidStateSource&>(vc).pidState();
  EXPECT_EQ(vsample.seq, 1u);
  EXPECT_DOUBLE_EQ(vsample.process_value, 1.0);
  EXPECT_DOUBLE_EQ(vsample.process_value_dot, 0.0);
  EXPECT_DOUBLE_EQ(vsample.error, 2.0);
  EXPECT_DOUBLE_EQ(vsample.command, 4.0);
  Car p;
  p.left_rear.interface = JointHandle::Interface::kVelocity;
  ControllerSpec ps = spec("p", "velocity_controllers/JointPositionController", "left_rear_wheel_joint");
  ps.params["pid"]["p"] = 3.0;
  auto& pc = p.load(ps);
  pc.setCommand(0.5);
  p.update(0.01);
  const PidStateSample& psample = dynamic_cast<const PidStateSource&>(pc).pidState();
  EXPECT_EQ(psample.seq, 1u);
  EXPECT_DOUBLE_EQ(psample.set_point, 0.5);
  EXPECT_DOUBLE_EQ(psample.command, 1.5);
  // A forwarding controller has no PID and no `state`.
  Car f;
  auto& fc = f.load(spec("f", "velocity_controllers/JointVelocityController", "left_rear_wheel_joint"));
  EXPECT_EQ(dynamic_cast<const PidStateSource*>(&fc), nullptr);
}

// Forwarding controllers pass commands on as they are (upstream's ForwardCommandController);
// the hardware enforces the joint's limits (tianracer_sim's test_sim_hw_sim).
TEST(ForwardCommandController, VelocityPassesThrough) {
  Car car;
  auto& c = car.load(spec("w", "velocity_controllers/JointVelocityController",
                          "left_rear_wheel_joint"));
  car.update(0.001);
  EXPECT_EQ(car.left_rear.command, 0.0);
  ASSERT_TRUE(c.setCommand(31.25));
  car.update(0.001);
  EXPECT_EQ(car.left_rear.command, 31.25);
  ASSERT_TRUE(c.setCommand(1e9));
  car.update(0.001);
  EXPECT_EQ(car.left_rear.command, 1e9);  // beyond the velocity limit 100: passed on
  EXPECT_FALSE(c.setCommand(kNan));
  car.update(0.001);
  EXPECT_EQ(car.left_rear.command, 1e9);
}

TEST(ForwardCommandController, VelocityWithNoLimitIsNotClamped) {
  Car car;
  car.left_rear.velocity_limit = 0.0;
  auto& c = car.load(spec("w", "velocity_controllers/JointVelocityController",
                          "left_rear_wheel_joint"));
  c.setCommand(1e6);
  car.update(0.001);
  EXPECT_EQ(car.left_rear.command, 1e6);
}

TEST(ForwardCommandController, PositionStartsAtCurrentPositionAndPassesOn) {
  Car car;
  car.pos_joint.position = 0.7;
  auto& c = car.load(spec("p", "position_controllers/JointPositionController", "pos_joint"));
  car.update(0.001);
  EXPECT_EQ(car.pos_joint.command, 0.7);
  c.setCommand(3.0);
  car.update(0.001);
  EXPECT_EQ(car.pos_joint.command, 3.0);  // past the upper limit 2: passed on
}

TEST(ForwardCommandController, EffortPassesOn) {
  Car car;
  auto& c = car.load(spec("e", "effort_controllers/JointEffortController",
                          "left_steering_hinge_joint"));
  c.setCommand(-50.0);
  car.update(0.001);
  EXPECT_EQ(car.left_hinge.command, -50.0);  // beyond the effort limit 10: passed on
}

TEST(JointStateController, DueAtPublishRateInSimTime) {
  ControllerSpec s;
  s.name = "joint_state_controller";
  s.type = "joint_state_controller/JointStateController";
  s.params["publish_rate"] = 50;
  Car car;
  car.load(s);
  auto* jsc = dynamic_cast<JointStateController*>(car.controllers.find("joint_state_controller"));
  ASSERT_NE(jsc, nullptr);
  EXPECT_EQ(jsc->publishRate(), 50.0);
  // 1 ms steps for 1 s: 50 messages, at t = 0, 0.02, 0.04, ...
  int count = 0;
  std::vector<int> steps;
  for (int k = 0; k < 1000; ++k) {
    if (jsc->due(k * 0.001)) {
      ++count;
      steps.push_back(k);
    }
  }
  EXPECT_EQ(count, 50);
  EXPECT_EQ(steps[1], 20);
  EXPECT_EQ(steps[49], 980);
  // A jump back in time (sim reset) restarts the schedule at once.
  EXPECT_TRUE(jsc->due(0.0005));
  EXPECT_FALSE(jsc->due(0.001));
  // A long gap gives one message, not a burst.
  EXPECT_TRUE(jsc->due(100.0));
  EXPECT_FALSE(jsc->due(100.001));
  EXPECT_TRUE(jsc->due(100.02));
}

TEST(ControllerSet, ResetClearsPidAndRestartsAtTheCurrentPosition) {
  Car car;
  ControllerSet set;
  auto& c = set.load(hingeSpec(1.0, 1.0, 0.0), car.joints);
  c.setCommand(0.5);
  for (int k = 0; k < 10; ++k) set.update(0.01);
  car.left_hinge.position = 0.2;
  set.reset(0.0);
  EXPECT_EQ(c.command(), 0.2);
  const auto* pc = dynamic_cast<const EffortJointPositionController*>(&c);
  ASSERT_NE(pc, nullptr);
  EXPECT_EQ(pc->pid().integrator(), 0.0);
  set.update(0.01);
  EXPECT_EQ(car.left_hinge.command, 0.0);
}

TEST(ControllerSet, UpdatesInOrderAndFindsByName) {
  Car car;
  ControllerSet set;
  set.load(spec("a", "velocity_controllers/JointVelocityController", "left_rear_wheel_joint"),
           car.joints);
  set.load(spec("b", "velocity_controllers/JointVelocityController", "right_rear_wheel_joint"),
           car.joints);
  ASSERT_EQ(set.size(), 2u);
  EXPECT_EQ(set.controllers()[0]->name(), "a");
  ASSERT_NE(set.find("b"), nullptr);
  EXPECT_EQ(set.find("b")->joint(), &car.right_rear);
  EXPECT_EQ(set.find("nope"), nullptr);
  set.find("b")->setCommand(3.0);
  set.update(0.001);
  EXPECT_EQ(car.right_rear.command, 3.0);
  EXPECT_EQ(car.left_rear.command, 0.0);
}

// ---------------------------------------------------------------------------- registry errors
TEST(ControllerRegistry, UnknownType) {
  Car car;
  const std::string e = errorOf(spec("x", "foo/Bar", "left_rear_wheel_joint"), car.joints);
  EXPECT_TRUE(startsWith(e, "controller 'x': unknown type 'foo/Bar'")) << e;
  EXPECT_NE(e.find("velocity_controllers/JointVelocityController"), std::string::npos) << e;
}

TEST(ControllerRegistry, MissingType) {
  Car car;
  EXPECT_EQ(errorOf(spec("x", "", "j"), car.joints), "controller 'x': no type given (parameter 'type')");
}

TEST(ControllerRegistry, MissingJoint) {
  Car car;
  const std::string e =
      errorOf(spec("wheel", "velocity_controllers/JointVelocityController", ""), car.joints);
  EXPECT_EQ(e, "controller 'wheel': no joint given (parameter 'joint' of "
               "velocity_controllers/JointVelocityController)");
}

TEST(ControllerRegistry, JointNotFound) {
  Car car;
  ControllerSpec s = spec("wheel", "velocity_controllers/JointVelocityController", "left_ front_wheel_joint");
  s.line = 7;
  const std::string e = errorOf(s, car.joints);
  EXPECT_TRUE(startsWith(e, "line 7: controller 'wheel': joint 'left_ front_wheel_joint' not "
                            "found among "
                            "the joints with a transmission (left_rear_wheel_joint, "))
      << e;
}

TEST(ControllerRegistry, InterfaceMismatchNamesBoth) {
  Car car;
  ControllerSpec s = hingeSpec(1.0);
  s.name = "rear_position";
  s.params["joint"] = "left_rear_wheel_joint";
  EXPECT_EQ(errorOf(s, car.joints),
            "controller 'rear_position': effort_controllers/JointPositionController needs the "
            "effort interface (EffortJointInterface) but the transmission of joint "
            "'left_rear_wheel_joint' gives the velocity interface (VelocityJointInterface)");
  EXPECT_EQ(errorOf(spec("h", "velocity_controllers/JointVelocityController",
                         "left_steering_hinge_joint"), car.joints),
            "controller 'h': velocity_controllers/JointVelocityController needs the velocity "
            "interface (VelocityJointInterface) but the transmission of joint "
            "'left_steering_hinge_joint' gives the effort interface (EffortJointInterface)");
}

TEST(ControllerRegistry, MissingPid) {
  Car car;
  ControllerSpec s = hingeSpec(1.0);
  s.params.erase("pid");
  EXPECT_EQ(errorOf(s, car.joints),
            "controller 'hinge': pid/p is missing (effort_controllers/JointPositionController "
            "needs pid gains)");
  s.params["pid"]["i"] = 1.0;  // pid present, p absent
  EXPECT_TRUE(startsWith(errorOf(s, car.joints), "controller 'hinge': pid/p is missing"));
  ControllerSpec v = spec("vel", "effort_controllers/JointVelocityController", "left_steering_hinge_joint");
  EXPECT_TRUE(startsWith(errorOf(v, car.joints), "controller 'vel': pid/p is missing"));
}

TEST(ControllerRegistry, BadPidValues) {
  Car car;
  ControllerSpec s = hingeSpec(1.0);
  s.params["pid"]["i_clamp_min"] = 1.0;
  s.params["pid"]["i_clamp_max"] = -1.0;
  EXPECT_EQ(errorOf(s, car.joints),
            "controller 'hinge': pid/i_clamp_min (1) is greater than pid/i_clamp_max (-1)");
  s = hingeSpec(kNan);
  EXPECT_EQ(errorOf(s, car.joints), "controller 'hinge': pid/p must be finite, got nan");
}

TEST(ControllerRegistry, JointStatePublishRate) {
  Car car;
  ControllerSpec s = spec("jsc", "joint_state_controller/JointStateController", "");
  EXPECT_EQ(errorOf(s, car.joints),
            "controller 'jsc': publish_rate is missing (joint_state_controller/JointStateController)");
  s.params["publish_rate"] = -5.0;
  EXPECT_EQ(errorOf(s, car.joints), "controller 'jsc': publish_rate must be a positive number, got -5");
  s.params["publish_rate"] = 50.0;
  EXPECT_EQ(errorOf(s, car.joints), "");
}

TEST(ControllerRegistry, UnknownKeysAreWarned) {
  Car car;
  ControllerSpec s = hingeSpec(1.0);
  s.params["pid"]["i_clamp"] = 0.5;
  s.params["pid"]["antiwindup"] = true;
  s.params["pid"]["pp"] = 2.0;
  s.params["joints"] = ParamValue::list({"a", "b"});
  s.line = 4;
  EXPECT_EQ(test::creationWarnings(s, car.joints),
            test::unusedKeyWarnings("line 4: controller 'hinge': ",
                                    "effort_controllers/JointPositionController",
                                    {"joints", "pid/pp"}));
}

TEST(ControllerRegistry, KeysOfAnotherTypeAreWarnedOncePerSubtree) {
  Car car;
  ControllerSpec s = spec("jsc", "joint_state_controller/JointStateController", "some_joint");
  s.params["publish_rate"] = 50;
  s.params["pid"]["p"] = 1.0;
  s.params["pid"]["d"] = 1.0;
  EXPECT_EQ(test::creationWarnings(s, car.joints),
            test::unusedKeyWarnings("controller 'jsc': ",
                                    "joint_state_controller/JointStateController",
                                    {"joint", "pid"}));
}

TEST(ControllerRegistry, EachClassChecksTheKindsOfItsKeys) {
  Car car;
  ControllerSpec s = hingeSpec(1.0);
  s.params["pid"]["p"] = "high";
  EXPECT_EQ(errorOf(s, car.joints), "controller 'hinge': pid/p must be a number, got a string");
  s = hingeSpec(1.0);
  s.params["pid"] = 1.0;
  EXPECT_EQ(errorOf(s, car.joints), "controller 'hinge': pid must be a dictionary, got a double");
  s = hingeSpec(1.0);
  s.params["pid"]["antiwindup"] = 1;
  EXPECT_EQ(errorOf(s, car.joints),
            "controller 'hinge': pid/antiwindup must be true or false, got an int");
  s = hingeSpec(1.0);
  s.params["joint"] = 3;
  EXPECT_EQ(errorOf(s, car.joints), "controller 'hinge': joint must be a string, got an int");
  ControllerSpec j = spec("jsc", "joint_state_controller/JointStateController", "");
  j.params["publish_rate"] = "fast";
  EXPECT_EQ(errorOf(j, car.joints),
            "controller 'jsc': publish_rate must be a number, got a string");
}

TEST(ControllerRegistry, ListsTheTypesInRegistrationOrderAndTakesNewOnes) {
  const std::vector<std::string> types = builtinControllers().types();
  const std::vector<std::string> expected = {
      "joint_state_controller/JointStateController", "effort_controllers/JointPositionController",
      "effort_controllers/JointVelocityController", "effort_controllers/JointEffortController",
      "velocity_controllers/JointVelocityController",
      "position_controllers/JointPositionController",
      "velocity_controllers/JointPositionController",
      "effort_controllers/JointGroupEffortController",
      "velocity_controllers/JointGroupVelocityController",
      "position_controllers/JointGroupPositionController",
      "effort_controllers/JointGroupPositionController",
      "diff_drive_controller/DiffDriveController",
      "ackermann_steering_controller/AckermannSteeringController",
      "four_wheel_steering_controller/FourWheelSteeringController",
      "position_controllers/JointTrajectoryController",
      "velocity_controllers/JointTrajectoryController",
      "effort_controllers/JointTrajectoryController",
      "position_controllers/GripperActionController",
      "effort_controllers/GripperActionController"};
  EXPECT_EQ(types, expected);

  // A registry of one's own: a new type is one factory and one add().
  ControllerRegistry registry;
  registry.add("my_controllers/Hold", [](ControllerContext& context) -> std::unique_ptr<Controller> {
    JointHandle* joint = SingleJointController::claimJoint(context, JointHandle::Interface::kEffort);
    const double gain = context.params.number("gain").value_or(1.0);
    return std::make_unique<EffortJointPositionController>(
        context.params.name(), joint, PidGains::fromIClamp(gain, 0.0, 0.0, 0.0));
  });
  EXPECT_TRUE(registry.has("my_controllers/Hold"));
  EXPECT_FALSE(registry.has("effort_controllers/JointPositionController"));
  Car car;
  ControllerSpec s = spec("hold", "my_controllers/Hold", "left_steering_hinge_joint");
  s.params["gain"] = 3.0;
  std::vector<std::string> warnings;
  auto c = registry.create(s, car.joints, [&](const std::string& w) { warnings.push_back(w); });
  EXPECT_EQ(c->joint(), &car.left_hinge);
  EXPECT_TRUE(warnings.empty());
  const std::string e = [&] {
    try {
      registry.create(hingeSpec(1.0), car.joints);
    } catch (const ControllerError& error) {
      return std::string(error.what());
    }
    return std::string();
  }();
  EXPECT_EQ(e, "controller 'hinge': unknown type 'effort_controllers/JointPositionController' "
               "(known types: my_controllers/Hold)");
}

TEST(ControllerRegistry, IntegralGainWithoutClampIsWarned) {
  Car car;
  std::vector<std::string> warnings;
  create(hingeSpec(1.0, 2.0), car.joints, [&](const std::string& w) { warnings.push_back(w); });
  ASSERT_EQ(warnings.size(), 1u);
  EXPECT_NE(warnings[0].find("integral term is always 0"), std::string::npos) << warnings[0];
}

TEST(ToPidGains, ClampRules) {
  PidParams p;
  p.p = 1.0;
  p.i_clamp = -2.0;
  PidGains g = toPidGains("c", p);
  EXPECT_EQ(g.i_clamp_min, -2.0);
  EXPECT_EQ(g.i_clamp_max, 2.0);
  EXPECT_FALSE(g.antiwindup);
  p.i_clamp_max = 3.0;  // the explicit bound wins over i_clamp
  p.antiwindup = true;
  g = toPidGains("c", p);
  EXPECT_EQ(g.i_clamp_min, -2.0);
  EXPECT_EQ(g.i_clamp_max, 3.0);
  EXPECT_TRUE(g.antiwindup);
}

TEST(ControllerSet, DuplicateNameAndJointConflict) {
  Car car;
  ControllerSet set;
  set.load(spec("a", "velocity_controllers/JointVelocityController", "left_rear_wheel_joint"),
           car.joints);
  try {
    set.load(spec("a", "velocity_controllers/JointVelocityController", "right_rear_wheel_joint"),
             car.joints);
    FAIL();
  } catch (const ControllerError& e) {
    EXPECT_STREQ(e.what(), "controller 'a': a controller of that name is loaded");
  }
  try {
    set.load(spec("b", "velocity_controllers/JointVelocityController", "left_rear_wheel_joint"),
             car.joints);
    FAIL();
  } catch (const ControllerError& e) {
    EXPECT_STREQ(e.what(), "controller 'b': joint 'left_rear_wheel_joint' is already commanded "
                           "by controller 'a'");
  }
  EXPECT_EQ(set.size(), 1u);
}
