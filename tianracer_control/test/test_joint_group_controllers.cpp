// The JointGroup controllers and velocity_controllers/JointPositionController: several joints
// per controller, their claims, upstream's refusals.
#include <cmath>
#include <limits>
#include <map>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "tianracer_control/controllers/joint_group_controller.h"
#include "tianracer_control/joint_controllers.h"

#include "control_test_support.h"

using namespace tianracer_control;  // NOLINT: test file

namespace {

using test::spec;

ControllerSpec groupSpec(const std::string& name, const std::string& type,
                         const std::vector<std::string>& joints) {
  ControllerSpec s = spec(name, type, "");
  ParamValue::List list;
  for (const std::string& j : joints) list.emplace_back(j);
  s.params["joints"] = ParamValue::list(list);
  return s;
}

std::string errorOf(const ControllerSpec& s, std::map<std::string, JointHandle*>& joints) {
  try {
    builtinControllers().create(s, joints);
  } catch (const ControllerError& e) {
    return e.what();
  }
  return "";
}

struct Car : test::SeedJoints {
  ControllerSet set;
  Car() {
    for (JointHandle* h : {&left_rear, &right_rear}) h->velocity_limit = 100.0;
  }
  JointGroupController& load(const ControllerSpec& s) {
    return dynamic_cast<JointGroupController&>(set.load(s, joints));
  }
};

const std::vector<std::string> kWheels = {"left_rear_wheel_joint", "right_rear_wheel_joint"};
const std::vector<std::string> kHinges = {"left_steering_hinge_joint",
                                          "right_steering_hinge_joint"};

}  // namespace

TEST(JointGroupController, ForwardsOneCommandPerJointAsItIs) {
  Car car;
  JointGroupController& c =
      car.load(groupSpec("wheels", JointGroupController::kVelocityType, kWheels));
  EXPECT_EQ(c.commands(), (std::vector<double>{0.0, 0.0}));  // velocity: starts at rest
  EXPECT_EQ(c.setCommands({3.0, -500.0}), "");
  car.set.update(0.01);
  EXPECT_EQ(car.left_rear.command, 3.0);
  EXPECT_EQ(car.right_rear.command, -500.0);  // beyond the velocity limit: the hardware's
}

TEST(JointGroupController, CommandOfTheWrongSizeIsRefusedWithUpstreamsMessage) {
  Car car;
  JointGroupController& c =
      car.load(groupSpec("wheels", JointGroupController::kVelocityType, kWheels));
  c.setCommands({1.0, 2.0});
  EXPECT_EQ(c.setCommands({1.0, 2.0, 3.0}),
            "Dimension of command (3) does not match number of joints (2)! Not executing!");
  EXPECT_EQ(c.setCommands({}),
            "Dimension of command (0) does not match number of joints (2)! Not executing!");
  const std::string nan = c.setCommands({5.0, std::numeric_limits<double>::quiet_NaN()});
  EXPECT_NE(nan.find("joint 'right_rear_wheel_joint'"), std::string::npos) << nan;
  EXPECT_EQ(c.commands(), (std::vector<double>{1.0, 2.0}));  // nothing changed
}

TEST(JointGroupController, PositionGroupHoldsTheCurrentPositionsOnStart) {
  Car car;
  car.left_hinge.interface = car.right_hinge.interface = JointHandle::Interface::kPosition;
  car.left_hinge.position = 0.2;
  car.right_hinge.position = 0.9;  // beyond the 0.6 limit: held where it is, as upstream
  JointGroupController& c =
      car.load(groupSpec("steer", JointGroupController::kPositionType, kHinges));
  EXPECT_EQ(c.commands(), (std::vector<double>{0.2, 0.9}));
  car.set.update(0.01);
  EXPECT_EQ(car.left_hinge.command, 0.2);
  EXPECT_EQ(c.setCommands({-1.0, 0.3}), "");
  car.set.update(0.01);
  EXPECT_EQ(car.left_hinge.command, -1.0);  // position_controllers' group forwards it
  EXPECT_EQ(car.right_hinge.command, 0.3);
}

TEST(JointGroupController, EffortPositionRunsOnePidPerJointWithItsOwnGains) {
  Car car;
  ControllerSpec s = groupSpec("steer", JointGroupController::kEffortPositionType, kHinges);
  s.params["left_steering_hinge_joint"]["pid"]["p"] = 10.0;
  s.params["right_steering_hinge_joint"]["pid"]["p"] = 2.0;
  s.params["right_steering_hinge_joint"]["pid"]["d"] = 0.5;
  JointGroupController& c = car.load(s);
  ASSERT_EQ(c.setCommands({0.1, 0.2}), "");
  car.set.update(0.01);
  EXPECT_DOUBLE_EQ(car.left_hinge.command, 1.0);   // 10 * 0.1
  EXPECT_DOUBLE_EQ(car.right_hinge.command, 0.4);  // 2 * 0.2, no derivative on the first step
  car.right_hinge.position = 0.1;                  // error 0.2 -> 0.1 in 0.01 s
  car.set.update(0.01);
  EXPECT_DOUBLE_EQ(car.right_hinge.command, 2.0 * 0.1 + 0.5 * (0.1 - 0.2) / 0.01);
  // Targets clamped to the position limits (upstream's enforceJointLimits: 0.9 -> 0.6); the
  // effort is the PID's, not clamped to the joint's effort limit (the hardware's).
  ASSERT_EQ(c.setCommands({0.9, 0.0}), "");
  EXPECT_EQ(c.commands()[0], 0.6);
  car.set.update(0.01);
  EXPECT_DOUBLE_EQ(car.left_hinge.command, 6.0);
  car.left_hinge.effort_limit = 1.0;
  car.set.update(0.01);
  EXPECT_DOUBLE_EQ(car.left_hinge.command, 6.0);
}

TEST(JointGroupController, ConfigurationErrors) {
  Car car;
  ControllerSpec none = spec("g", JointGroupController::kEffortType, "");
  EXPECT_EQ(errorOf(none, car.joints),
            "controller 'g': Failed to getParam 'joints' "
            "(effort_controllers/JointGroupEffortController needs a list of joints)");
  EXPECT_EQ(errorOf(groupSpec("g", JointGroupController::kEffortType, {}), car.joints),
            "controller 'g': List of joint names is empty.");
  ControllerSpec scalar = spec("g", JointGroupController::kEffortType, "");
  scalar.params["joints"] = "left_steering_hinge_joint";
  EXPECT_EQ(errorOf(scalar, car.joints),
            "controller 'g': joints must be a list of strings, got a string");
  EXPECT_EQ(errorOf(groupSpec("g", JointGroupController::kEffortType,
                              {"left_steering_hinge_joint", "left_steering_hinge_joint"}),
                    car.joints),
            "controller 'g': joint 'left_steering_hinge_joint' is listed twice in joints");
  const std::string iface =
      errorOf(groupSpec("g", JointGroupController::kEffortType, kWheels), car.joints);
  EXPECT_NE(iface.find("needs the effort interface (EffortJointInterface) but the transmission "
                       "of joint 'left_rear_wheel_joint' gives the velocity interface"),
            std::string::npos)
      << iface;
  const std::string missing =
      errorOf(groupSpec("g", JointGroupController::kVelocityType, {"left_rear_wheel_joint", "nope"}),
              car.joints);
  EXPECT_NE(missing.find("joint 'nope' not found"), std::string::npos) << missing;
  ControllerSpec pid = groupSpec("g", JointGroupController::kEffortPositionType, kHinges);
  pid.params["left_steering_hinge_joint"]["pid"]["p"] = 1.0;
  EXPECT_EQ(errorOf(pid, car.joints),
            "controller 'g': right_steering_hinge_joint/pid/p is missing "
            "(effort_controllers/JointGroupPositionController needs pid gains)");
}

TEST(JointGroupController, ClaimsEveryJointSoThatNoOtherControllerMayRunOnOne) {
  Car car;
  ControllerSet set;
  set.loadController(groupSpec("wheels", JointGroupController::kVelocityType, kWheels), car.joints);
  set.loadController(spec("left", "velocity_controllers/JointVelocityController",
                          "right_rear_wheel_joint"),
                     car.joints);
  const std::vector<ClaimedResources> claims = ControllerSet::claimedResources(*set.find("wheels"));
  ASSERT_EQ(claims.size(), 1u);
  EXPECT_EQ(claims[0].hardware_interface, "hardware_interface::VelocityJointInterface");
  EXPECT_EQ(claims[0].resources, kWheels);
  try {
    set.switchControllers({"wheels", "left"}, {}, Strictness::kStrict, 0.0);
    ADD_FAILURE() << "no conflict";
  } catch (const ControllerError& e) {
    EXPECT_EQ(std::string(e.what()),
              "Resource conflict on [right_rear_wheel_joint].  Controllers = [wheels, left, ]\n"
              "Could not switch controllers, due to resource conflict");
  }
  // At start-up (ControllerSet::add) a second writer of a joint is refused.
  Car other;
  other.set.load(groupSpec("wheels", JointGroupController::kVelocityType, kWheels), other.joints);
  EXPECT_THROW(other.set.load(spec("l", "velocity_controllers/JointVelocityController",
                                   "left_rear_wheel_joint"),
                              other.joints),
               ControllerError);
}

TEST(VelocityJointPositionController, VelocityFromThePositionError) {
  Car car;
  car.left_rear.continuous = false;
  car.left_rear.has_position_limits = true;
  car.left_rear.lower = -1.0;
  car.left_rear.upper = 1.0;
  car.left_rear.position = 0.25;
  ControllerSpec s = spec("pos", "velocity_controllers/JointPositionController",
                          "left_rear_wheel_joint");
  s.params["pid"]["p"] = 4.0;
  Controller& c = car.set.load(s, car.joints);
  car.set.update(0.01);
  EXPECT_EQ(car.left_rear.command, 0.0);  // holds where it started
  EXPECT_TRUE(c.setCommand(5.0));         // clamped to the upper limit
  car.set.update(0.01);
  EXPECT_DOUBLE_EQ(car.left_rear.command, 4.0 * (1.0 - 0.25));
  EXPECT_FALSE(c.setCommand(std::nan("")));
  car.left_rear.velocity_limit = 1.0;  // the velocity is the PID's; the hardware limits it
  car.set.update(0.01);
  EXPECT_DOUBLE_EQ(car.left_rear.command, 3.0);
  // A continuous joint takes the shorter way round.
  car.right_rear.position = 3.0;
  ControllerSpec w = spec("wrap", "velocity_controllers/JointPositionController",
                          "right_rear_wheel_joint");
  w.params["pid"]["p"] = 1.0;
  Controller& wrap = car.set.load(w, car.joints);
  wrap.setCommand(-3.0);
  car.set.update(0.01);
  EXPECT_NEAR(car.right_rear.command, 2.0 * M_PI - 6.0, 1e-12);
}
