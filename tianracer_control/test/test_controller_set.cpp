// A robot's controllers as controller_manager handles them: load, switch, unload, with its
// rules and error texts (ros_control's controller_manager.cpp).
#include <map>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "tianracer_control/joint_controllers.h"

#include "control_test_support.h"

using namespace tianracer_control;  // NOLINT: test file

namespace {

using test::spec;

struct Car {
  JointHandle hinge, wheel;
  std::map<std::string, JointHandle*> joints;
  Car() {
    hinge.name = "hinge_joint";
    hinge.interface = JointHandle::Interface::kEffort;
    hinge.has_position_limits = true;
    hinge.lower = -0.6;
    hinge.upper = 0.6;
    hinge.effort_limit = 10.0;
    wheel.name = "wheel_joint";
    wheel.interface = JointHandle::Interface::kVelocity;
    wheel.velocity_limit = 100.0;
    joints = {{hinge.name, &hinge}, {wheel.name, &wheel}};
  }
};

ControllerSpec wheelSpec(const std::string& name) {
  return spec(name, "velocity_controllers/JointVelocityController", "wheel_joint");
}

ControllerSpec jscSpec() {
  ControllerSpec s = spec("jsc", "joint_state_controller/JointStateController", "");
  s.params["publish_rate"] = 50;
  return s;
}

template <typename F>
std::string errorOf(F&& f) {
  try {
    f();
  } catch (const ControllerError& e) {
    return e.what();
  }
  return "";
}

// "w" (the wheel's velocity controller) loaded, "jsc" loaded and running.
void loadWheelAndRunJsc(ControllerSet& set, Car& car) {
  set.loadController(wheelSpec("w"), car.joints);
  set.loadController(jscSpec(), car.joints);
  set.switchControllers({"jsc"}, {}, Strictness::kStrict, 0.0);
}

std::vector<std::string> states(const ControllerSet& set) {
  std::vector<std::string> out;
  for (const auto& c : set.controllers()) out.push_back(c->name() + ":" + toString(set.state(*c)));
  return out;
}

}  // namespace

TEST(ControllerManager, LoadKeepsItInitializedUntilStarted) {
  Car car;
  ControllerSet set;
  Controller& w = set.loadController(wheelSpec("w"), car.joints);
  set.loadController(jscSpec(), car.joints);
  EXPECT_EQ(states(set), (std::vector<std::string>{"w:initialized", "jsc:initialized"}));
  // Not running: no update writes the joint.
  car.wheel.command = 7.0;
  w.setCommand(3.0);
  set.update(0.001);
  EXPECT_EQ(car.wheel.command, 7.0);

  set.switchControllers({"w", "jsc"}, {}, Strictness::kStrict, 1.5);
  EXPECT_EQ(states(set), (std::vector<std::string>{"w:running", "jsc:running"}));
  EXPECT_EQ(w.command(), 0.0);  // starting(): a velocity controller starts at 0
  w.setCommand(3.0);
  set.update(0.001);
  EXPECT_EQ(car.wheel.command, 3.0);

  set.switchControllers({}, {"w"}, Strictness::kStrict, 2.0);
  EXPECT_EQ(states(set), (std::vector<std::string>{"w:stopped", "jsc:running"}));
  car.wheel.command = 0.5;
  w.setCommand(9.0);
  set.update(0.001);
  EXPECT_EQ(car.wheel.command, 0.5);  // a stopped controller writes nothing

  set.unloadController("w");
  EXPECT_EQ(states(set), (std::vector<std::string>{"jsc:running"}));
  EXPECT_EQ(set.find("w"), nullptr);
}

TEST(ControllerManager, LoadErrorsAreControllerManagersTexts) {
  Car car;
  ControllerSet set;
  set.loadController(wheelSpec("w"), car.joints);
  EXPECT_EQ(errorOf([&] { set.loadController(wheelSpec("w"), car.joints); }),
            "A controller named 'w' was already loaded inside the controller manager");
  EXPECT_EQ(errorOf([&] {
              set.loadController(spec("dd", "no_such_controllers/NoSuchController", ""),
                                 car.joints);
            }),
            "Could not load controller 'dd' because controller type "
            "'no_such_controllers/NoSuchController' does not exist.\n"
            "Use 'rosservice call controller_manager/list_controller_types' to get the available "
            "types");
  EXPECT_EQ(errorOf([&] {
              set.loadController(spec("bad", "velocity_controllers/JointVelocityController",
                                      "no_joint"),
                                 car.joints);
            }),
            "controller 'bad': joint 'no_joint' not found among the joints with a transmission "
            "(hinge_joint, wheel_joint)\nInitializing controller 'bad' failed");
  ControllerSpec untyped;
  untyped.name = "untyped";
  EXPECT_EQ(errorOf([&] { set.loadController(untyped, car.joints); }),
            "Could not load controller 'untyped' because the type was not specified.");
  EXPECT_EQ(set.size(), 1u);  // nothing of a failed load stays
}

TEST(ControllerManager, StrictSwitchRefusesAndChangesNothing) {
  Car car;
  ControllerSet set;
  loadWheelAndRunJsc(set, car);
  EXPECT_EQ(errorOf([&] { set.switchControllers({"w", "nope"}, {}, Strictness::kStrict, 0.0); }),
            "Could not start controller with name 'nope' because no controller with this name "
            "exists");
  EXPECT_EQ(errorOf([&] { set.switchControllers({}, {"nope"}, Strictness::kStrict, 0.0); }),
            "Could not stop controller with name 'nope' because no controller with this name "
            "exists");
  EXPECT_EQ(errorOf([&] { set.switchControllers({}, {"w"}, Strictness::kStrict, 0.0); }),
            "Could not stop controller 'w' since it is not running");
  EXPECT_EQ(errorOf([&] { set.switchControllers({"jsc", "w"}, {}, Strictness::kStrict, 0.0); }),
            "Controller 'jsc' is already running");
  EXPECT_EQ(errorOf([&] { set.switchControllers({"jsc"}, {"jsc"}, Strictness::kBestEffort, 0.0); }),
            "Could no start or stop controller 'jsc' because of conflicting switching command");
  EXPECT_EQ(states(set), (std::vector<std::string>{"w:initialized", "jsc:running"}));
}

TEST(ControllerManager, BestEffortSkipsWhatCannotBeDone) {
  Car car;
  ControllerSet set;
  loadWheelAndRunJsc(set, car);
  set.switchControllers({"w", "jsc", "nope"}, {"also_nope"}, Strictness::kBestEffort, 0.0);
  EXPECT_EQ(states(set), (std::vector<std::string>{"w:running", "jsc:running"}));
  set.switchControllers({}, {"w", "w", "nope"}, Strictness::kBestEffort, 0.0);
  EXPECT_EQ(states(set), (std::vector<std::string>{"w:stopped", "jsc:running"}));
}

TEST(ControllerManager, TwoControllersOnOneJointMayLoadButNotRunTogether) {
  Car car;
  ControllerSet set;
  set.loadController(wheelSpec("a"), car.joints);
  set.loadController(wheelSpec("b"), car.joints);
  set.switchControllers({"a"}, {}, Strictness::kStrict, 0.0);
  EXPECT_EQ(errorOf([&] { set.switchControllers({"b"}, {}, Strictness::kStrict, 0.0); }),
            "Resource conflict on [wheel_joint].  Controllers = [a, b, ]\n"
            "Could not switch controllers, due to resource conflict");
  // Swapping them in one switch is fine.
  set.switchControllers({"b"}, {"a"}, Strictness::kStrict, 0.0);
  EXPECT_EQ(states(set), (std::vector<std::string>{"a:stopped", "b:running"}));
}

TEST(ControllerManager, UnloadErrors) {
  Car car;
  ControllerSet set;
  set.loadController(wheelSpec("w"), car.joints);
  set.switchControllers({"w"}, {}, Strictness::kStrict, 0.0);
  EXPECT_EQ(errorOf([&] { set.unloadController("w"); }),
            "Could not unload controller with name 'w' because it is still running");
  EXPECT_EQ(errorOf([&] { set.unloadController("nope"); }),
            "Could not unload controller with name 'nope' because no controller with this name "
            "exists");
  EXPECT_EQ(set.size(), 1u);
}

TEST(ControllerManager, ClaimedResourcesNameInterfaceAndJoint) {
  Car car;
  ControllerSet set;
  ControllerSpec hinge = spec("h", "effort_controllers/JointPositionController", "hinge_joint");
  hinge.params["pid"]["p"] = 1.0;
  const Controller& h = set.loadController(hinge, car.joints);
  const Controller& j = set.loadController(jscSpec(), car.joints);
  const auto rh = ControllerSet::claimedResources(h);
  ASSERT_EQ(rh.size(), 1u);
  EXPECT_EQ(rh[0].hardware_interface, "hardware_interface::EffortJointInterface");
  EXPECT_EQ(rh[0].resources, std::vector<std::string>{"hinge_joint"});
  const auto rj = ControllerSet::claimedResources(j);
  ASSERT_EQ(rj.size(), 1u);
  EXPECT_EQ(rj[0].hardware_interface, "hardware_interface::JointStateInterface");
  EXPECT_TRUE(rj[0].resources.empty());
}

TEST(ControllerManager, ResetRestartsOnlyRunningControllers) {
  Car car;
  ControllerSet set;
  ControllerSpec hinge = spec("h", "effort_controllers/JointPositionController", "hinge_joint");
  hinge.params["pid"]["p"] = 1.0;
  Controller& h = set.loadController(hinge, car.joints);
  h.setCommand(0.4);
  car.hinge.position = 0.1;
  set.reset(0.0);
  EXPECT_EQ(h.command(), 0.4);  // not running: not restarted
  set.switchControllers({"h"}, {}, Strictness::kStrict, 0.0);
  EXPECT_EQ(h.command(), 0.1);  // starting(): hold the current position
  h.setCommand(0.4);
  car.hinge.position = 0.2;
  set.reset(0.0);
  EXPECT_EQ(h.command(), 0.2);
}
