// XmlRpc parameter trees -> ControllerSpec (no roscore needed).
#include <gtest/gtest.h>

#include "tianracer_control/ros/controller_adapter.h"

using namespace tianracer_control;  // NOLINT: test file
using XmlRpc::XmlRpcValue;

namespace {
std::string errorOf(const std::string& name, const XmlRpcValue& v) {
  try {
    toControllerSpec(name, v);
  } catch (const ControllerError& e) {
    return e.what();
  }
  return "";
}
}  // namespace

TEST(ControllerAdapter, KeepsTheWholeTreeForTheClassToRead) {
  XmlRpcValue v;
  v["type"] = "effort_controllers/JointPositionController";
  v["joint"] = "left_steering_hinge_joint";
  v["pid"]["p"] = 1;  // an int, as YAML gives "p: 1"
  v["pid"]["d"] = 0.05;
  v["pid"]["i_clamp"] = 0.5;
  v["pid"]["antiwindup"] = true;
  v["joints"][0] = "a";
  const ControllerSpec s = toControllerSpec("hinge", v);
  EXPECT_EQ(s.name, "hinge");
  EXPECT_EQ(s.type, "effort_controllers/JointPositionController");
  ControllerSpec copy = s;
  ControllerParams params(copy);
  EXPECT_EQ(params.text("joint"), "left_steering_hinge_joint");
  EXPECT_EQ(params.number("pid/p"), 1.0);
  EXPECT_EQ(params.number("pid/d"), 0.05);
  EXPECT_FALSE(params.number("pid/i").has_value());
  EXPECT_EQ(params.number("pid/i_clamp"), 0.5);
  EXPECT_EQ(params.boolean("pid/antiwindup"), true);
  ASSERT_NE(s.params.find("joints"), nullptr);
  EXPECT_EQ(s.params.find("joints")->kind(), ParamValue::Kind::kList);
  EXPECT_EQ(params.unread(), std::vector<std::string>{"joints"});
}

TEST(ControllerAdapter, JointStateController) {
  XmlRpcValue v;
  v["type"] = "joint_state_controller/JointStateController";
  v["publish_rate"] = 50;
  std::map<std::string, JointHandle*> joints;
  const auto c = builtinControllers().create(toControllerSpec("joint_state_controller", v), joints);
  const auto* jsc = dynamic_cast<const JointStateController*>(c.get());
  ASSERT_NE(jsc, nullptr);
  EXPECT_EQ(jsc->publishRate(), 50.0);
}

TEST(ControllerAdapter, WrongTypesNameTheController) {
  XmlRpcValue not_struct = 3;
  EXPECT_EQ(errorOf("c", not_struct),
            "controller 'c': its parameters must be a dictionary, got an int");
  XmlRpcValue v;
  v["type"] = 5;
  EXPECT_EQ(errorOf("c", v), "controller 'c': type must be a string, got an int");
  // The other keys are the class's to check (test_joint_controllers).
  XmlRpcValue w;
  w["type"] = "effort_controllers/JointPositionController";
  w["pid"]["p"] = "high";
  EXPECT_EQ(errorOf("c", w), "");
}

TEST(ControllerAdapter, EveryTypeWithTopicsHasItsRosSide) {
  // joint_state_controller's joint_states are the node's; every other type has topics.
  for (const std::string& type : builtinControllers().types()) {
    if (type == "joint_state_controller/JointStateController") {
      EXPECT_EQ(findRosSide(type), nullptr) << type;
    } else {
      EXPECT_NE(findRosSide(type), nullptr) << type;
    }
  }
  EXPECT_EQ(findRosSide("no_such_controllers/NoSuchController"), nullptr);
}
