// A ros_control YAML read without ROS: the same specs as the parameter-server adapter gives
// (test_controller_adapter.cpp), the shipped file, and each bad input's message.
#include <cmath>
#include <gtest/gtest.h>

#include "tianracer_control/controller_yaml.h"

#include "control_test_support.h"

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

/// The error of creating the one controller under /ns of `yaml` (joint 'j', effort).
std::string createErrorOf(const std::string& yaml) {
  JointHandle j;
  j.name = "j";
  j.interface = JointHandle::Interface::kEffort;
  std::map<std::string, JointHandle*> joints{{j.name, &j}};
  try {
    for (const ControllerSpec& spec : loadControllerYaml(yaml, "test.yaml", "ns")) {
      builtinControllers().create(spec, joints, WarningSink());
    }
  } catch (const ControllerError& e) {
    return e.what();
  }
  return "";
}

double numberOf(const ControllerSpec& spec, const std::string& key) {
  ControllerParams params(spec);
  return params.number(key).value_or(-1.0);
}

}  // namespace

TEST(ControllerYaml, ShippedFileLoadsEveryControllerSorted) {
  const std::string file = TIANRACER_CONTROL_DIR "/config/tianracer_control.yaml";
  const std::vector<ControllerSpec> specs = loadControllerYamlFile(file, "/tianracer");
  ASSERT_EQ(specs.size(), 5u);
  EXPECT_EQ(specs[0].name, "joint_state_controller");
  EXPECT_EQ(numberOf(specs[0], "publish_rate"), 50.0);
  EXPECT_EQ(specs[1].name, "left_rear_wheel_velocity_controller");
  EXPECT_EQ(specs[1].type, "velocity_controllers/JointVelocityController");
  ASSERT_NE(specs[1].params.find("joint"), nullptr);
  EXPECT_EQ(specs[1].params.find("joint")->asString(), "left_rear_wheel_joint");
  EXPECT_EQ(specs[2].name, "left_steering_hinge_position_controller");
  EXPECT_EQ(numberOf(specs[2], "pid/p"), 20.0);
  EXPECT_EQ(numberOf(specs[2], "pid/d"), 0.2);
  EXPECT_EQ(specs[2].source, file);
  EXPECT_GT(specs[2].line, 0);
  // Each builds: the loader gives what the controller classes read.
  JointHandle hinge;
  hinge.name = "left_steering_hinge_joint";
  hinge.interface = JointHandle::Interface::kEffort;
  std::map<std::string, JointHandle*> joints{{hinge.name, &hinge}};
  std::vector<std::string> warnings;
  EXPECT_NO_THROW(warnings = test::creationWarnings(specs[2], joints));
  EXPECT_TRUE(warnings.empty()) << warnings.front();
}

TEST(ControllerYaml, SameTreeAsTheParameterServer) {
  const std::vector<ControllerSpec> specs = loadControllerYaml(
      "ns:\n"
      "  hinge:\n"
      "    type: effort_controllers/JointPositionController\n"
      "    joint: left_steering_hinge_joint\n"
      "    pid: {p: 1, d: 0.05, i_clamp: 0.5, antiwindup: true, pp: 2}\n"
      "    names: [a, 'b']\n",
      "test.yaml", "ns");
  ASSERT_EQ(specs.size(), 1u);
  const ControllerSpec& s = specs[0];
  EXPECT_EQ(s.name, "hinge");
  EXPECT_EQ(s.type, "effort_controllers/JointPositionController");
  // rosparam's typing: 1 an int, 0.05 a double, true a bool, the list kept.
  const ParamValue* pid = s.params.find("pid");
  ASSERT_NE(pid, nullptr);
  EXPECT_EQ(pid->find("p")->kind(), ParamValue::Kind::kInt);
  EXPECT_EQ(pid->find("d")->kind(), ParamValue::Kind::kDouble);
  EXPECT_EQ(pid->find("antiwindup")->kind(), ParamValue::Kind::kBool);
  EXPECT_EQ(pid->find("i"), nullptr);
  ASSERT_EQ(s.params.find("names")->items().size(), 2u);
  EXPECT_EQ(s.params.find("names")->items()[1].asString(), "b");
  EXPECT_EQ(s.source, "test.yaml");
  EXPECT_EQ(s.line, 3);
  // Keys the class does not read are warned at the file and line, as from the server.
  JointHandle hinge;
  hinge.name = "left_steering_hinge_joint";
  hinge.interface = JointHandle::Interface::kEffort;
  std::map<std::string, JointHandle*> joints{{hinge.name, &hinge}};
  EXPECT_EQ(test::creationWarnings(s, joints),
            test::unusedKeyWarnings("test.yaml:3: controller 'hinge': ",
                                    "effort_controllers/JointPositionController",
                                    {"names", "pid/pp"}));
}

// A number as getParam reads a double: an int or a double; the hardware readers' one check.
TEST(ControllerYaml, ParamNumbersAreIntsOrDoublesAndFiniteNumbersAreChecked) {
  EXPECT_EQ(ParamValue(3).asNumber(), 3.0);
  EXPECT_EQ(ParamValue(0.25).asNumber(), 0.25);
  EXPECT_FALSE(ParamValue(true).asNumber());
  EXPECT_FALSE(ParamValue("1").asNumber());
  EXPECT_FALSE(ParamValue().asNumber());
  EXPECT_EQ(finiteNumberProblem(ParamValue(2)), "");
  EXPECT_EQ(finiteNumberProblem(ParamValue(-1e300)), "");
  EXPECT_EQ(finiteNumberProblem(ParamValue("fast")), "is a string, not a number");
  EXPECT_EQ(finiteNumberProblem(ParamValue::list()), "is a list, not a number");
  EXPECT_EQ(finiteNumberProblem(ParamValue(std::nan(""))), "is nan, not a finite number");
  EXPECT_EQ(finiteNumberProblem(ParamValue(-HUGE_VAL)), "is -inf, not a finite number");
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
            "test.yaml:1: controller 'c': type must be a string, got an int");
  // A key of the wrong kind: named by the class that reads it, at the controller's line.
  EXPECT_EQ(createErrorOf("ns:\n  c:\n    type: effort_controllers/JointPositionController\n"
                          "    joint: j\n    pid: {p: high}\n"),
            "test.yaml:3: controller 'c': pid/p must be a number, got a string");
  EXPECT_EQ(createErrorOf("ns:\n  c:\n    type: effort_controllers/JointPositionController\n"
                          "    joint: j\n    pid: {p: '1'}\n"),
            "test.yaml:3: controller 'c': pid/p must be a number, got a string");
  EXPECT_EQ(createErrorOf("ns:\n  c:\n    type: effort_controllers/JointPositionController\n"
                          "    joint: j\n    pid: 1.0\n"),
            "test.yaml:3: controller 'c': pid must be a dictionary, got a double");
  EXPECT_EQ(errorOf("ns: {c: 3}\n", "ns", {"c"}),
            "test.yaml:1: controller 'c': its parameters must be a dictionary, got an int");
  EXPECT_EQ(errorOf("ns: {c: {type: t}}\n", "ns", {"d"}),
            "controller 'd': no parameters at /ns/d in test.yaml");
  EXPECT_EQ(errorOf("other: {c: {type: t}}\n", "/ns"),
            "test.yaml: no controllers under /ns (the YAML's top key is the controllers' "
            "namespace, e.g. tianracer:)");
  EXPECT_EQ(errorOf("ns: [1, 2]\n", "ns"), "test.yaml: /ns is not a dictionary of controllers");
  EXPECT_EQ(errorOf("ns: {c: [\n", "ns").rfind("test.yaml:2: not valid YAML: ", 0), 0u)
      << errorOf("ns: {c: [\n", "ns");
  try {
    loadControllerYamlFile("/nonexistent/control.yaml", "ns");
    FAIL();
  } catch (const ControllerError& e) {
    EXPECT_STREQ(e.what(), "controller YAML /nonexistent/control.yaml: cannot be read");
  }
}
