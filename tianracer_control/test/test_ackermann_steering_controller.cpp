// ackermann_steering_controller/AckermannSteeringController without ROS: its keys and
// upstream's errors, the geometry from the URDF, commands and the bicycle odometry.
#include <cmath>
#include <limits>
#include <map>
#include <string>

#include <gtest/gtest.h>
#include <urdf_parser/urdf_parser.h>

#include "tianracer_control/controllers/ackermann_steering_controller.h"
#include "tianracer_control/joint_controllers.h"

#include "control_test_support.h"

using namespace tianracer_control;  // NOLINT: test file

namespace {

// upstream's test robot in short: the steer joint 1.0 m ahead of the rear wheel joint, a rear
// wheel of 0.3 m radius; `wheel` replaces the rear wheel's collision geometry.
std::string steerbot(const std::string& wheel = "<cylinder radius=\"0.3\" length=\"0.1\"/>") {
  return R"(<robot name="steerbot">
  <link name="base_link"/><link name="front_steer"/>
  <link name="rear_wheel"><collision><geometry>)" + wheel + R"(</geometry></collision></link>
  <joint name="rear_wheel_joint" type="continuous"><parent link="base_link"/><child link="rear_wheel"/>
    <origin xyz="-0.5 0 0"/><axis xyz="0 1 0"/></joint>
  <joint name="front_steer_joint" type="revolute"><parent link="base_link"/><child link="front_steer"/>
    <origin xyz="0.5 0 0"/><axis xyz="0 0 1"/><limit lower="-0.5" upper="0.5" effort="10" velocity="5"/></joint>
</robot>)";
}

struct Bot {
  JointHandle rear, steer;
  std::map<std::string, JointHandle*> joints;
  urdf::ModelInterfaceSharedPtr urdf;
  ControllerSet set;

  explicit Bot(const std::string& xml = steerbot()) : urdf(urdf::parseURDF(xml)) {
    rear.name = "rear_wheel_joint";
    rear.interface = JointHandle::Interface::kVelocity;
    rear.continuous = true;
    steer.name = "front_steer_joint";
    steer.interface = JointHandle::Interface::kPosition;
    steer.has_position_limits = true;
    steer.lower = -0.5;
    steer.upper = 0.5;
    joints = {{rear.name, &rear}, {steer.name, &steer}};
    set.setRobotDescription(urdf.get());
  }
  AckermannSteeringController& load(const ControllerSpec& s) {
    return dynamic_cast<AckermannSteeringController&>(set.load(s, joints));
  }
  std::string errorOf(const ControllerSpec& s) {
    try {
      builtinControllers().create(s, joints, WarningSink(), urdf.get());
    } catch (const ControllerError& e) {
      return e.what();
    }
    return "";
  }
  /// The joints follow their commands for dt (the steer at once), then the update at t.
  void step(double t, double dt) {
    rear.position += rear.command * dt;
    steer.position = steer.command;
    set.update(dt, t);
  }
};

ControllerSpec spec() {
  return test::spec("ack", AckermannSteeringController::kType, "");
}

}  // namespace

TEST(AckermannSteeringController, DefaultJointNamesAndGeometryFromTheUrdf) {
  Bot bot;
  AckermannSteeringController& c = bot.load(spec());
  EXPECT_EQ(c.params().rear_wheel, "rear_wheel_joint");
  EXPECT_EQ(c.params().front_steer, "front_steer_joint");
  EXPECT_DOUBLE_EQ(c.params().wheel_separation_h, 1.0);  // |x rear - x steer|
  EXPECT_DOUBLE_EQ(c.params().wheel_radius, 0.3);
  const std::vector<ClaimedResources> claims = ControllerSet::claimedResources(c);
  ASSERT_EQ(claims.size(), 2u);
  EXPECT_EQ(claims[0].hardware_interface, "hardware_interface::VelocityJointInterface");
  EXPECT_EQ(claims[1].hardware_interface, "hardware_interface::PositionJointInterface");
}

TEST(AckermannSteeringController, AngularZIsTheSteeringAngleAndOdometryIsTheBicycle) {
  Bot bot;
  ControllerSpec s = spec();
  s.params["cmd_vel_timeout"] = 100.0;
  AckermannSteeringController& c = bot.load(s);
  ASSERT_TRUE(c.setCommand(0.6, 0.2));
  const double dt = 1.0 / 256;
  double t = 0.0;
  bot.step(t += dt, dt);
  EXPECT_DOUBLE_EQ(bot.rear.command, 0.6 / 0.3);
  EXPECT_DOUBLE_EQ(bot.steer.command, 0.2);
  for (int i = 1; i < 256; ++i) bot.step(t += dt, dt);
  // After the first update: v = 0.6, yaw rate = v tan(0.2) / 1.0, for 1 - dt s.
  const double w = 0.6 * std::tan(0.2), span = 1.0 - dt;
  EXPECT_NEAR(c.odometry().heading(), w * span, 1e-9);
  EXPECT_NEAR(c.odometry().x(), 0.6 / w * std::sin(w * span), 1e-9);
  EXPECT_NEAR(c.odometry().linear(), 0.6, 1e-9);
  EXPECT_NEAR(c.odometry().angular(), w, 1e-9);
  // The steer target goes to the joint as it is (upstream's updateCommand sets
  // front_steer_joint_.setCommand(angular)); the hardware enforces its limits. NaN is ignored.
  c.setCommand(0.6, 2.0);
  bot.step(t += dt, dt);
  EXPECT_DOUBLE_EQ(bot.steer.command, 2.0);
  EXPECT_FALSE(c.setCommand(std::numeric_limits<double>::quiet_NaN(), 0.0));
  // Timeout: both joints to rest.
  Bot quiet;
  AckermannSteeringController& q = quiet.load(spec());  // cmd_vel_timeout 0.5
  q.setCommand(0.6, 0.2);
  double u = 0.0;
  for (int i = 0; i < 256; ++i) quiet.step(u += dt, dt);
  EXPECT_EQ(quiet.rear.command, 0.0);
  EXPECT_EQ(quiet.steer.command, 0.0);
}

TEST(AckermannSteeringController, ConfigurationErrorsAreUpstreams) {
  const std::string pre = "controller 'ack': ";
  Bot bot;
  ControllerSpec s = spec();
  s.params["rear_wheel"] = "missing_joint";
  EXPECT_EQ(bot.errorOf(s), pre + "missing_joint couldn't be retrieved from model description");
  Bot sphere(steerbot("<sphere radius=\"0.3\"/>"));  // ackermann takes cylinders only
  EXPECT_EQ(sphere.errorOf(spec()), pre + "Wheel link rear_wheel is NOT modeled as a cylinder!\n" +
                                        pre + "Couldn't retrieve rear_wheel_joint wheel radius");
  try {
    builtinControllers().create(spec(), bot.joints);
    ADD_FAILURE();
  } catch (const ControllerError& e) {
    EXPECT_EQ(std::string(e.what()), pre + "Robot descripion couldn't be retrieved from param server.");
  }
  s = spec();
  s.params["front_steer"] = "rear_wheel_joint";  // a velocity joint
  s.params["wheel_separation_h"] = 1.0;
  s.params["wheel_radius"] = 0.3;
  const std::string e = bot.errorOf(s);
  EXPECT_NE(e.find("needs the position interface (PositionJointInterface) but the transmission of "
                   "joint 'rear_wheel_joint' gives the velocity interface"),
            std::string::npos)
      << e;
  s = spec();
  s.params["rear_wheel"] = 1;
  EXPECT_EQ(bot.errorOf(s), pre + "rear_wheel must be a string, got an int");
  s = spec();
  s.params["publish_cmd"] = true;  // a diff drive key: warned, not read
  std::vector<std::string> warnings;
  builtinControllers().create(s, bot.joints, [&](const std::string& w) { warnings.push_back(w); },
                              bot.urdf.get());
  EXPECT_EQ(warnings, (std::vector<std::string>{pre + "key 'publish_cmd' is not used by " +
                                                AckermannSteeringController::kType + ", ignored"}));
}
