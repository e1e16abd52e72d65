// The one robot set-up (simulator/robot_setup.h) that the node and the Python environment share:
// the robot's name and namespace, where its controllers are read when no control namespace is
// given, which it gets, and the warning when none are found; here on a controller YAML as the
// Python environment reads it (the node's parameter-server source is tested by the
// robot_setup rostest against this one).
#include <gtest/gtest.h>

#include <cstdio>
#include <fstream>
#include <string>

#include "tianracer_sim/simulator/robot_setup.h"

#include "tianracer_sim/model/robot_model.h"

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

// A robot with gazebo_ros_control in namespace `ns` ("" = none) and no sensors.
RobotModel robot(const std::string& ns, const std::string& urdf_name = "car") {
  const std::string plugin =
      ns == "-" ? "" : "<gazebo><plugin name='c' filename='libgazebo_ros_control.so'><robotNamespace>" +
                           ns + "</robotNamespace></plugin></gazebo>";
  const std::string urdf =
      "<robot name='" + urdf_name + "'><link name='base'><inertial><mass value='1'/><inertia "
      "ixx='1' iyy='1' izz='1' ixy='0' ixz='0' iyz='0'/></inertial></link>" + plugin + "</robot>";
  return loadRobotModel(urdf, "test.urdf", LoadOptions());
}

std::vector<std::string> names(const RobotSetup& s) {
  std::vector<std::string> out;
  for (const auto& c : s.controllers) out.push_back(c.name);
  return out;
}

TEST(SetUpRobot, NameAndNamespace) {
  const YamlControlParams none("");
  RobotSetupRequest request;
  // The gazebo_ros_control namespace names the robot.
  RobotSetup s = setUpRobot(robot("/racer"), request, none);
  EXPECT_EQ(s.name, "racer");
  EXPECT_EQ(s.ns, "/racer");
  // No namespace: the URDF's name, and the namespace after it (gazebo_ros_control's default).
  s = setUpRobot(robot(""), request, none);
  EXPECT_EQ(s.name, "car");
  EXPECT_EQ(s.ns, "/car");
  // robotNamespace "/": the root namespace, as gazebo_ros_control's NodeHandle("/") (the
  // ros_controllers test robots' controller manager); the robot is named after the URDF.
  s = setUpRobot(robot("/"), request, none);
  EXPECT_EQ(s.name, "car");
  EXPECT_EQ(s.ns, "/");
  // ~robot_name other than the namespace: a warning, the controllers stay under the namespace.
  request.robot_name = "other";
  s = setUpRobot(robot("/racer"), request, none);
  EXPECT_EQ(s.name, "other");
  EXPECT_EQ(s.ns, "/racer");
  ASSERT_EQ(s.warnings.size(), 2u);  // and: no controllers
  EXPECT_NE(s.warnings[0].find("~robot_name is 'other' but the model's gazebo_ros_control "
                               "robotNamespace is '/racer'"), std::string::npos) << s.warnings[0];
  // spawn_urdf_model's name wins, without a warning.
  request.spawn_name = "spawned";
  s = setUpRobot(robot("/racer"), request, none);
  EXPECT_EQ(s.name, "spawned");
  EXPECT_EQ(s.warnings.size(), 1u);
}

TEST(SetUpRobot, ControllersFromTheYamlByTheNodesRules) {
  const std::string file = writeYaml("two.yaml", kTwoRobots);
  const YamlControlParams yaml(file);
  RobotSetupRequest request;
  request.control_config = file;
  // Under the robot's namespace: every controller there, sorted.
  RobotSetup s = setUpRobot(robot("/car_a"), request, yaml);
  EXPECT_EQ(s.control_ns, "/car_a");
  EXPECT_EQ(names(s), (std::vector<std::string>{"joint_state_controller"}));
  EXPECT_TRUE(s.warnings.empty());
  EXPECT_TRUE(s.notes.empty());
  // Nothing under the robot's namespace and two keys with controllers: no guess, a warning.
  s = setUpRobot(robot("/racer"), request, yaml);
  EXPECT_TRUE(s.controllers.empty());
  ASSERT_EQ(s.warnings.size(), 1u);
  EXPECT_NE(s.warnings[0].find("pass control_key:=car_a"), std::string::npos) << s.warnings[0];
  // One key with controllers: it, with a note.
  const std::string one = writeYaml("one.yaml", "tianracer:\n  jsc: {type: joint_state_controller/JointStateController}\n"
                                                "  w: {type: velocity_controllers/JointVelocityController, joint: w}\n");
  request.control_config = one;
  s = setUpRobot(robot("/racer"), request, YamlControlParams(one));
  EXPECT_EQ(s.control_ns, "/tianracer");
  EXPECT_EQ(names(s), (std::vector<std::string>{"jsc", "w"}));
  ASSERT_EQ(s.notes.size(), 1u);
  EXPECT_NE(s.notes[0].find("controllers of /racer read from /tianracer, the one key of " + one),
            std::string::npos) << s.notes[0];
  // Asked for by name and namespace.
  request.control_namespace = "tianracer";
  request.controllers = std::vector<std::string>{"w"};
  s = setUpRobot(robot("/racer"), request, YamlControlParams(one));
  EXPECT_EQ(names(s), (std::vector<std::string>{"w"}));
  EXPECT_EQ(s.controllers[0].type, "velocity_controllers/JointVelocityController");
  // A spawned robot waits for a spawner unless told otherwise.
  request = RobotSetupRequest();
  request.control_config = one;
  request.spawn_name = "late";
  request.waits_for_spawner = true;
  s = setUpRobot(robot("/tianracer"), request, YamlControlParams(one));
  EXPECT_TRUE(s.controllers.empty());
  EXPECT_TRUE(s.warnings.empty());
}

TEST(SetUpRobot, ErrorsAreTheParameterServersErrors) {
  const std::string one = writeYaml("one.yaml", "tianracer:\n  jsc: {type: joint_state_controller/JointStateController}\n");
  RobotSetupRequest request;
  request.controllers = std::vector<std::string>{"missing"};
  // A controller asked for that is not there, whether or not its namespace is.
  for (const std::string& ns : {"tianracer", "nowhere"}) {
    request.control_namespace = ns;
    try {
      setUpRobot(robot("/racer"), request, YamlControlParams(one));
      ADD_FAILURE() << "no error";
    } catch (const tianracer_control::ControllerError& e) {
      EXPECT_NE(std::string(e.what()).find("controller 'missing': no parameters at /" + ns + "/missing"),
                std::string::npos) << e.what();
    }
  }
  // A YAML that does not parse is an error naming the file.
  const std::string bad = writeYaml("bad.yaml", "a: [1, 2\n");
  try {
    YamlControlParams params(bad);
    ADD_FAILURE() << "no error";
  } catch (const tianracer_control::ControllerError& e) {
    EXPECT_NE(std::string(e.what()).find(bad), std::string::npos) << e.what();
  }
}

}  // namespace
}  // namespace tianracer_sim
