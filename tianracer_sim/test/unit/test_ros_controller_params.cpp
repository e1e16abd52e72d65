// Where a robot's controllers are read when no control namespace is given, and the warning when
// none are found (no roscore: the parameter-server part is a bool here).
#include <gtest/gtest.h>

#include <cstdio>
#include <fstream>
#include <string>

#include "tianracer_sim/ros/controller_params.h"

namespace tianracer_sim {
namespace {

std::string writeYaml(const std::string& name, const std::string& text) {
  const std::string path = ::testing::TempDir() + name;
  std::ofstream(path) << text;
  return path;
}

const char* kTwoRobots = R"(car_a:
  joint_state_controller: {type: joint_state_controller/JointStateController, publish_rate: 50}
car_b:
  wheel: {type: velocity_controllers/JointVelocityController, joint: w}
use_sim_time: true
notes: {author: me}
)";

TEST(ControlConfigKeys, TopLevelKeysAndThoseWithControllers) {
  const ControlConfigKeys k = readControlConfigKeys(writeYaml("two.yaml", kTwoRobots));
  EXPECT_EQ(k.error, "");
  EXPECT_EQ(k.keys, (std::vector<std::string>{"car_a", "car_b", "use_sim_time", "notes"}));
  EXPECT_EQ(k.with_controllers, (std::vector<std::string>{"car_a", "car_b"}));
}

TEST(ControlConfigKeys, UnreadableFileIsAnError) {
  const ControlConfigKeys missing = readControlConfigKeys("/nonexistent/ctrl.yaml");
  EXPECT_NE(missing.error, "");
  const ControlConfigKeys list = readControlConfigKeys(writeYaml("list.yaml", "- a\n- b\n"));
  EXPECT_EQ(list.error, "its top level is not a dictionary");
}

TEST(ChooseControlNamespace, TheRobotsNamespaceWhenItHasControllers) {
  const ControlConfigKeys one = readControlConfigKeys(
      writeYaml("one.yaml", "tianracer:\n  jsc: {type: joint_state_controller/JointStateController}\n"));
  EXPECT_EQ(chooseControlNamespace("/racecar", true, one), "/racecar");
  // None under the robot's namespace: the YAML's only key with controllers (the shipped YAML
  // for a car given another name).
  EXPECT_EQ(chooseControlNamespace("/other", false, one), "tianracer");
  // Two candidates: no guess.
  const ControlConfigKeys two = readControlConfigKeys(writeYaml("two.yaml", kTwoRobots));
  EXPECT_EQ(chooseControlNamespace("/racecar", false, two), "/racecar");
  // No YAML named: the robot's namespace.
  EXPECT_EQ(chooseControlNamespace("/racecar", false, ControlConfigKeys()), "/racecar");
}

TEST(NoControllersWarning, NamesTheNamespaceAndTheKeys) {
  const std::string file = writeYaml("two.yaml", kTwoRobots);
  EXPECT_EQ(noControllersWarning("racecar", "/racecar", readControlConfigKeys(file)),
            "robot 'racecar' has gazebo_ros_control but no controller: none is defined under "
            "/racecar (a dictionary with a 'type' key); control_config " + file +
                " has the top-level keys [car_a, car_b, use_sim_time, notes]: pass "
                "control_key:=car_a (or key the YAML by the robot's namespace)");
  EXPECT_EQ(noControllersWarning("r", "/r", ControlConfigKeys()),
            "robot 'r' has gazebo_ros_control but no controller: none is defined under /r (a "
            "dictionary with a 'type' key); load the controller YAML (rosparam load) under /r, "
            "or give ~control_namespace");
  const std::string text =
      noControllersWarning("r", "/r", readControlConfigKeys("/nonexistent/ctrl.yaml"));
  EXPECT_NE(text.find("control_config /nonexistent/ctrl.yaml could not be read: "),
            std::string::npos)
      << text;
}

}  // namespace
}  // namespace tianracer_sim
