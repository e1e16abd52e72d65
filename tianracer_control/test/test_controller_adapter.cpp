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

TEST(ControllerAdapter, PositionControllerWithPid) {
  XmlRpcValue v;
  v["type"] = "effort_controllers/JointPositionController";
  v["joint"] = "left_steering_hinge_joint";
  v["pid"]["p"] = 1;  // an int, as YAML gives "p: 1"
  v["pid"]["d"] = 0.05;
  v["pid"]["i_clamp"] = 0.5;
  v["pid"]["antiwindup"] = true;
  const ControllerSpec s = toControllerSpec("hinge", v);
  EXPECT_EQ(s.name, "hinge");
  EXPECT_EQ(s.type, "effort_controllers/JointPositionController");
  EXPECT_EQ(s.joint, "left_steering_hinge_joint");
  ASSERT_TRUE(s.pid.has_value());
  EXPECT_EQ(*s.pid->p, 1.0);
  EXPECT_EQ(*s.pid->d, 0.05);
  EXPECT_FALSE(s.pid->i.has_value());
  EXPECT_EQ(*s.pid->i_clamp, 0.5);
  EXPECT_TRUE(*s.pid->antiwindup);
  EXPECT_FALSE(s.publish_rate.has_value());
  const std::vector<std::string> keys = {"joint", "pid", "pid/antiwindup", "pid/d",
                                         "pid/i_clamp", "pid/p", "type"};
  EXPECT_EQ(s.keys, keys);
}

TEST(ControllerAdapter, JointStateController) {
  XmlRpcValue v;
  v["type"] = "joint_state_controller/JointStateController";
  v["publish_rate"] = 50;
  const ControllerSpec s = toControllerSpec("joint_state_controller", v);
  ASSERT_TRUE(s.publish_rate.has_value());
  EXPECT_EQ(*s.publish_rate, 50.0);
}

TEST(ControllerAdapter, WrongTypesNameTheController) {
  XmlRpcValue not_struct = 3;
  EXPECT_EQ(errorOf("c", not_struct),
            "controller 'c': its parameters must be a dictionary, got an int");
  XmlRpcValue v;
  v["type"] = 5;
  EXPECT_EQ(errorOf("c", v), "controller 'c': type must be a string, got an int");
  XmlRpcValue w;
  w["type"] = "effort_controllers/JointPositionController";
  w["pid"]["p"] = "high";
  EXPECT_EQ(errorOf("c", w), "controller 'c': pid/p must be a number, got a string");
  XmlRpcValue x;
  x["pid"] = 1.0;
  EXPECT_EQ(errorOf("c", x), "controller 'c': pid must be a dictionary, got a double");
  XmlRpcValue y;
  y["pid"]["antiwindup"] = 1;
  EXPECT_EQ(errorOf("c", y), "controller 'c': pid/antiwindup must be true or false, got an int");
}
