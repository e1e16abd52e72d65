// A ros_control YAML read without ROS: the same specs as the parameter-server adapter gives
// (test_controller_adapter.cpp), the shipped file, and each bad input's message.
#include <gtest/gtest.h>

#include "tianracer_control/controller_yaml.h"

using namespace tianracer_control;  // NOLINT: test file

namespace {

std::string errorOf(const std::string& yaml, const std::string& ns,
                    const std::vector<std::string>& names = {}) {
  try {
    loadControllerYaml(yaml, "test.yaml", ns, names);
  } catch (const ControllerError& e) {
    return e.what();
  }
  return "";
}

}  // namespace

TEST(ControllerYaml, ShippedFileLoadsEveryControllerSorted) {
  const std::vector<ControllerSpec> specs = loadControllerYamlFile(
      TIANRACER_CONTROL_DIR "/config/tianracer_control.yaml", "/tianracer");
  ASSERT_EQ(specs.size(), 5u);
  EXPECT_EQ(specs[0].name, "joint_state_controller");
  EXPECT_EQ(*specs[0].publish_rate, 50.0);
  EXPECT_EQ(specs[1].name, "left_rear_wheel_velocity_controller");
  EXPECT_EQ(specs[1].type, "velocity_controllers/JointVelocityController");
  EXPECT_EQ(specs[1].joint, "left_rear_wheel_joint");
  EXPECT_EQ(specs[2].name, "left_steering_hinge_position_controller");
  ASSERT_TRUE(specs[2].pid.has_value());
  EXPECT_EQ(*specs[2].pid->p, 20.0);
  EXPECT_EQ(*specs[2].pid->d, 0.2);
  EXPECT_GT(specs[2].line, 0);
  // Each builds: the loader gives what makeController() expects.
  JointHandle hinge;
  hinge.name = "left_steering_hinge_joint";
  hinge.interface = JointHandle::Interface::kEffort;
  std::map<std::string, JointHandle*> joints{{hinge.name, &hinge}};
  EXPECT_NO_THROW(makeController(specs[2], joints));
}

TEST(ControllerYaml, SameSpecAsTheParameterServer) {
  const std::vector<ControllerSpec> specs = loadControllerYaml(
      "ns:\n"
      "  hinge:\n"
      "    type: effort_controllers/JointPositionController\n"
      "    joint: left_steering_hinge_joint\n"
      "    pid: {p: 1, d: 0.05, i_clamp: 0.5, antiwindup: true}\n",
      "test.yaml", "ns");
  ASSERT_EQ(specs.size(), 1u);
  const ControllerSpec& s = specs[0];
  EXPECT_EQ(s.name, "hinge");
  EXPECT_EQ(*s.pid->p, 1.0);
  EXPECT_EQ(*s.pid->d, 0.05);
  EXPECT_FALSE(s.pid->i.has_value());
  EXPECT_EQ(*s.pid->i_clamp, 0.5);
  EXPECT_TRUE(*s.pid->antiwindup);
  const std::vector<std::string> keys = {"joint", "pid", "pid/antiwindup", "pid/d",
                                         "pid/i_clamp", "pid/p", "type"};
  EXPECT_EQ(s.keys, keys);  // unknown keys stay for makeController()'s warning
  EXPECT_EQ(s.line, 3);
}

TEST(ControllerYaml, NestedNamespaceTopLevelAndNamedControllers) {
  const std::string yaml =
      "a:\n  b:\n    c1: {type: t1, joint: j1}\n    c2: {type: t2, joint: j2}\n    other: 3\n";
  EXPECT_EQ(loadControllerYaml(yaml, "x", "/a/b/").size(), 2u);  // 'other' is no controller
  const auto picked = loadControllerYaml(yaml, "x", "a/b", {"c2"});
  ASSERT_EQ(picked.size(), 1u);
  EXPECT_EQ(picked[0].type, "t2");
  EXPECT_EQ(loadControllerYaml("c: {type: t}\n", "x", "").size(), 1u);
}

TEST(ControllerYaml, BadInputNamesFileLineAndKey) {
  EXPECT_EQ(errorOf("ns: {c: {type: 5}}\n", "ns"),
            "controller 'c': type must be a string, got an int (test.yaml, line 1)");
  EXPECT_EQ(errorOf("ns:\n  c:\n    type: t\n    pid: {p: high}\n", "ns"),
            "controller 'c': pid/p must be a number, got a string (test.yaml, line 4)");
  EXPECT_EQ(errorOf("ns:\n  c:\n    type: t\n    pid: {p: '1'}\n", "ns"),
            "controller 'c': pid/p must be a number, got a string (test.yaml, line 4)");
  EXPECT_EQ(errorOf("ns: {c: {type: t, pid: 1.0}}\n", "ns"),
            "controller 'c': pid must be a dictionary, got a double (test.yaml, line 1)");
  EXPECT_EQ(errorOf("ns: {c: {type: t, pid: {antiwindup: 1}}}\n", "ns"),
            "controller 'c': pid/antiwindup must be true or false, got an int (test.yaml, line 1)");
  EXPECT_EQ(errorOf("ns: {c: 3}\n", "ns", {"c"}),
            "controller 'c': its parameters must be a dictionary, got an int (test.yaml, line 1)");
  EXPECT_EQ(errorOf("ns: {c: {type: t}}\n", "ns", {"d"}),
            "controller 'd': no parameters at /ns/d in test.yaml");
  EXPECT_EQ(errorOf("other: {c: {type: t}}\n", "/ns"),
            "test.yaml: no controllers under /ns (the YAML's top key is the controllers' "
            "namespace, e.g. tianracer:)");
  EXPECT_EQ(errorOf("ns: [1, 2]\n", "ns"), "test.yaml: /ns is not a dictionary of controllers");
  EXPECT_EQ(errorOf("ns: {c: [\n", "ns").rfind("test.yaml: not valid YAML: ", 0), 0u);
  try {
    loadControllerYamlFile("/nonexistent/control.yaml", "ns");
    FAIL();
  } catch (const ControllerError& e) {
    EXPECT_STREQ(e.what(), "controller YAML /nonexistent/control.yaml: cannot be read");
  }
}
