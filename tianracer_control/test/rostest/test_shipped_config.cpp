// config/tianracer_control.yaml on the parameter server -> specs -> controllers on the seed's
// joints, and their command topics. Needs a roscore (rostest), not the simulator.
#include <algorithm>
#include <cmath>
#include <functional>
#include <limits>
#include <map>
#include <string>
#include <vector>

#include <gtest/gtest.h>
#include <ros/ros.h>
#include <std_msgs/Float64.h>

#include "tianracer_control/controllers/effort_joint_position_controller.h"
#include "tianracer_control/ros/controller_adapter.h"

#include "../control_test_support.h"
#include "spin_until.h"

using namespace tianracer_control;  // NOLINT: test file

namespace {

// Every key under the namespace whose value has a "type": the controllers of the file.
std::vector<std::string> controllerNames(const ros::NodeHandle& ns) {
  XmlRpc::XmlRpcValue tree;
  std::vector<std::string> names;
  if (!ns.getParam("", tree) || tree.getType() != XmlRpc::XmlRpcValue::TypeStruct) return names;
  for (auto it = tree.begin(); it != tree.end(); ++it) {
    if (it->second.getType() == XmlRpc::XmlRpcValue::TypeStruct && it->second.hasMember("type")) {
      names.push_back(it->first);
    }
  }
  return names;
}

bool waitFor(const std::function<bool()>& done, double seconds) {
  return test::spinUntil(done, seconds, 0.01);
}

}  // namespace

TEST(ShippedConfig, LoadsUnchangedWithoutWarnings) {
  ros::NodeHandle ns("/tianracer");
  const std::vector<std::string> names = controllerNames(ns);
  ASSERT_EQ(names.size(), 5u);
  test::SeedJoints seed;
  ControllerSet set;
  std::vector<std::string> warnings;
  for (const ControllerSpec& spec : loadControllerSpecs(ns, names)) {
    set.load(spec, seed.joints, 0.0, [&](const std::string& w) { warnings.push_back(w); });
  }
  EXPECT_TRUE(warnings.empty()) << warnings.front();
  auto* jsc = dynamic_cast<JointStateController*>(set.find("joint_state_controller"));
  ASSERT_NE(jsc, nullptr);
  EXPECT_EQ(jsc->publishRate(), 50.0);
  const auto* hinge = dynamic_cast<const EffortJointPositionController*>(
      set.find("left_steering_hinge_position_controller"));
  ASSERT_NE(hinge, nullptr);
  EXPECT_EQ(hinge->pid().gains().p, 20.0);
  EXPECT_EQ(hinge->pid().gains().d, 0.2);
  ASSERT_NE(set.find("right_rear_wheel_velocity_controller"), nullptr);
  EXPECT_EQ(set.find("right_rear_wheel_velocity_controller")->joint(), &seed.right_rear);
}

TEST(ShippedConfig, MissingControllerIsNamed) {
  ros::NodeHandle ns("/tianracer");
  try {
    loadControllerSpecs(ns, {"front_wheel_controller"});
    FAIL();
  } catch (const ControllerError& e) {
    EXPECT_STREQ(e.what(),
                 "controller 'front_wheel_controller': no parameters at "
                 "/tianracer/front_wheel_controller");
  }
}

TEST(ShippedConfig, CommandTopicsReachTheControllers) {
  ros::NodeHandle ns("/tianracer");
  test::SeedJoints seed;
  ControllerSet set;
  for (const ControllerSpec& spec : loadControllerSpecs(ns, controllerNames(ns))) {
    set.load(spec, seed.joints);
  }
  ControllerCommandSubscribers subs(ns, set);
  const std::vector<std::string> topics = subs.topics();
  EXPECT_EQ(topics.size(), 4u);  // not the joint_state_controller
  EXPECT_NE(std::find(topics.begin(), topics.end(),
                      "/tianracer/left_rear_wheel_velocity_controller/command"),
            topics.end());

  ros::NodeHandle nh;
  ros::Publisher wheel =
      nh.advertise<std_msgs::Float64>("/tianracer/left_rear_wheel_velocity_controller/command", 1);
  ros::Publisher hinge = nh.advertise<std_msgs::Float64>(
      "/tianracer/right_steering_hinge_position_controller/command", 1);
  ASSERT_TRUE(waitFor([&] { return wheel.getNumSubscribers() > 0 && hinge.getNumSubscribers() > 0; },
                      10.0));
  std_msgs::Float64 m;
  m.data = 12.5;
  wheel.publish(m);
  m.data = 5.0;  // beyond the hinge limit: clamped to 0.6
  hinge.publish(m);
  Controller* w = set.find("left_rear_wheel_velocity_controller");
  Controller* h = set.find("right_steering_hinge_position_controller");
  ASSERT_TRUE(waitFor([&] {
    subs.apply();
    return w->command() == 12.5 && h->command() == 0.6;
  }, 10.0));
  set.update(0.001);
  EXPECT_EQ(seed.left_rear.command, 12.5);

  // NaN is dropped; the command stays.
  m.data = std::numeric_limits<double>::quiet_NaN();
  wheel.publish(m);
  m.data = 0.3;
  hinge.publish(m);  // sent after the NaN: once it arrives, the NaN has been handled
  ASSERT_TRUE(waitFor([&] {
    subs.apply();
    return h->command() == 0.3;
  }, 10.0));
  EXPECT_EQ(w->command(), 12.5);
}

int main(int argc, char** argv) {
  testing::InitGoogleTest(&argc, argv);
  ros::init(argc, argv, "test_shipped_config");
  ros::NodeHandle keep_alive;
  return RUN_ALL_TESTS();
}
