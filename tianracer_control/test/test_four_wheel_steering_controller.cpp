// four_wheel_steering_controller/FourWheelSteeringController without ROS: the geometry from the
// URDF as urdf_geometry_parser measures it, upstream's errors, the twist and four-wheel-steering
// commands' wheel speeds and angles, which command wins, the timeout, and the odometry fed back
// its own commands.
#include <cmath>
#include <map>
#include <string>

#include <gtest/gtest.h>
#include <urdf_parser/urdf_parser.h>

#include "tianracer_control/controllers/four_wheel_steering_controller.h"
#include "tianracer_control/joint_controllers.h"
#include "control_test_support.h"

using namespace tianracer_control;  // NOLINT: test file

namespace {

// Wheel base 1.0 m, track 0.8 m (between the wheel joints), each wheel 0.02 m outside its
// steering joint, wheels of 0.1 m radius.
std::string fourWs() {
  std::string s = R"(<robot name="fws"><link name="base_link"/>)";
  const char* names[4] = {"front_left", "front_right", "rear_left", "rear_right"};
  const double x[4] = {0.5, 0.5, -0.5, -0.5}, y[4] = {0.38, -0.38, 0.38, -0.38}, off[4] = {0.02, -0.02, 0.02, -0.02};
  for (int i = 0; i < 4; ++i) {
    const std::string n = names[i];
    s += "<link name='" + n + "_steer'/><link name='" + n +
         "_wheel'><collision><geometry><cylinder radius='0.1' length='0.05'/></geometry></collision></link>"
         "<joint name='" + n + "_steering_joint' type='revolute'><parent link='base_link'/><child link='" + n +
         "_steer'/><origin xyz='" + std::to_string(x[i]) + " " + std::to_string(y[i]) +
         " 0'/><axis xyz='0 0 1'/><limit lower='-1.5' upper='1.5' effort='10' velocity='5'/></joint>"
         "<joint name='" + n + "_wheel_joint' type='continuous'><parent link='" + n + "_steer'/><child link='" + n +
         "_wheel'/><origin xyz='0 " + std::to_string(off[i]) + " 0'/><axis xyz='0 1 0'/></joint>";
  }
  return s + "</robot>";
}

struct Bot {
  JointHandle h[8];  // wheels fl fr rl rr, then steering fl fr rl rr
  std::map<std::string, JointHandle*> joints;
  urdf::ModelInterfaceSharedPtr urdf;
  ControllerSet set;
  Bot() : urdf(urdf::parseURDF(fourWs())) {
    const char* names[4] = {"front_left", "front_right", "rear_left", "rear_right"};
    for (int i = 0; i < 4; ++i) {
      h[i].name = std::string(names[i]) + "_wheel_joint";
      h[i].interface = JointHandle::Interface::kVelocity;
      h[i].continuous = true;
      h[4 + i].name = std::string(names[i]) + "_steering_joint";
      h[4 + i].interface = JointHandle::Interface::kPosition;
    }
    for (JointHandle& j : h) joints[j.name] = &j;
    set.setRobotDescription(urdf.get());
  }
  FourWheelSteeringController& load(const ControllerSpec& s) {
    return dynamic_cast<FourWheelSteeringController&>(set.load(s, joints));
  }
  std::string errorOf(const ControllerSpec& s, const urdf::ModelInterface* description) {
    try {
      builtinControllers().create(s, joints, WarningSink(), description);
    } catch (const ControllerError& e) {
      return e.what();
    }
    return "";
  }
  /// Joints follow their commands exactly for dt, then the controllers update at time t.
  void step(double t, double dt) {
    for (int i = 0; i < 4; ++i) {
      h[i].velocity = h[i].command;
      h[i].position += h[i].command * dt;
      h[4 + i].position = h[4 + i].command;
    }
    set.update(dt, t);
  }
};

ControllerSpec spec() {
  ControllerSpec s = test::spec("fws", FourWheelSteeringController::kType, "");
  s.params["front_wheel"] = ParamValue::list({ParamValue("front_left_wheel_joint"), ParamValue("front_right_wheel_joint")});
  s.params["rear_wheel"] = ParamValue::list({ParamValue("rear_left_wheel_joint"), ParamValue("rear_right_wheel_joint")});
  s.params["front_steering"] =
      ParamValue::list({ParamValue("front_left_steering_joint"), ParamValue("front_right_steering_joint")});
  s.params["rear_steering"] =
      ParamValue::list({ParamValue("rear_left_steering_joint"), ParamValue("rear_right_steering_joint")});
  return s;
}

}  // namespace

TEST(FourWheelSteeringController, GeometryFromTheUrdfAsUrdfGeometryParserMeasuresIt) {
  Bot bot;
  const FourWheelSteeringController& c = bot.load(spec());
  EXPECT_NEAR(c.params().track, 0.8, 1e-12);
  EXPECT_NEAR(c.params().wheel_base, 1.0, 1e-12);
  EXPECT_NEAR(c.params().wheel_radius, 0.1, 1e-12);
  EXPECT_NEAR(c.params().wheel_steering_y_offset, 0.02, 1e-12);
  EXPECT_EQ(c.claimedJoints().size(), 8u);
  // Parameters win over the URDF (the steering offset always comes from it).
  ControllerSpec s = spec();
  s.params["track"] = 0.9;
  s.params["wheel_radius"] = 0.2;
  s.params["wheel_base"] = 1.2;
  Bot other;
  const FourWheelSteeringController& d = other.load(s);
  EXPECT_EQ(d.params().track, 0.9);
  EXPECT_EQ(d.params().wheel_radius, 0.2);
  EXPECT_EQ(d.params().wheel_base, 1.2);
}

TEST(FourWheelSteeringController, ConfigurationErrorsAreUpstreams) {
  Bot bot;
  ControllerSpec s = spec();
  s.params.erase("front_wheel");
  EXPECT_NE(bot.errorOf(s, bot.urdf.get()).find("Couldn't retrieve wheel param 'front_wheel'."), std::string::npos);
  s = spec();
  s.params["rear_wheel"] = ParamValue("rear_left_wheel_joint");
  EXPECT_NE(bot.errorOf(s, bot.urdf.get()).find("#front wheels (2) != #rear wheels (1)."), std::string::npos);
  s = spec();
  s.params["front_wheel"] = ParamValue("front_left_wheel_joint");
  s.params["rear_wheel"] = ParamValue("rear_left_wheel_joint");
  EXPECT_NE(bot.errorOf(s, bot.urdf.get()).find("#two wheels by axle (left and right) is needed; now : 1 ."),
            std::string::npos);
  s = spec();
  s.params["rear_steering"] = ParamValue("rear_left_steering_joint");
  EXPECT_NE(bot.errorOf(s, bot.urdf.get()).find("#left steerings (2) != #right steerings (1)."), std::string::npos);
  EXPECT_NE(bot.errorOf(spec(), nullptr).find("Robot descripion couldn't be retrieved from param server."),
            std::string::npos);
  s = spec();
  s.params["front_wheel"] = ParamValue::list({ParamValue("no_such_joint"), ParamValue("front_right_wheel_joint")});
  EXPECT_NE(bot.errorOf(s, bot.urdf.get()).find("no_such_joint couldn't be retrieved from model description"),
            std::string::npos);
  s = spec();
  s.params["base_frame_id"] = "chassis";  // not an ancestor of the joints
  EXPECT_NE(bot.errorOf(s, bot.urdf.get()).find("base_link couldn't be retrieved from model description or his parent joint"),
            std::string::npos);
}

// updateCommand()'s twist branch: both axles steer, the rear opposite to the front.
TEST(FourWheelSteeringController, TwistSteersBothAxlesOpposite) {
  Bot bot;
  FourWheelSteeringController& c = bot.load(spec());
  ASSERT_TRUE(c.setTwist(1.0, 0.0, 0.5));
  bot.step(0.01, 0.01);
  const double b = 1.0, st = 0.76, r = 0.1, off = 0.02, v = 1.0, w = 0.5;
  EXPECT_NEAR(bot.h[4].command, std::atan(w * b / (2 * v - w * st)), 1e-12);
  EXPECT_NEAR(bot.h[5].command, std::atan(w * b / (2 * v + w * st)), 1e-12);
  EXPECT_NEAR(bot.h[6].command, -bot.h[4].command, 1e-12);
  EXPECT_NEAR(bot.h[7].command, -bot.h[5].command, 1e-12);
  EXPECT_NEAR(bot.h[0].command, std::hypot(v - w * st / 2, b * w / 2) / r - w * off / r, 1e-12);
  EXPECT_NEAR(bot.h[1].command, std::hypot(v + w * st / 2, b * w / 2) / r + w * off / r, 1e-12);
  EXPECT_NEAR(bot.h[2].command, bot.h[0].command, 1e-12);
  EXPECT_FALSE(c.setTwist(std::nan(""), 0.0, 0.0));  // NaN: ignored
}

// The four-wheel-steering branch: equal angles crab sideways at the commanded speed.
TEST(FourWheelSteeringController, EqualAxleAnglesCrab) {
  Bot bot;
  FourWheelSteeringController& c = bot.load(spec());
  ASSERT_TRUE(c.setFourWheelSteering(0.3, 0.3, 0.5));
  bot.step(0.01, 0.01);
  for (int i = 0; i < 4; ++i) {
    EXPECT_NEAR(bot.h[4 + i].command, 0.3, 1e-12) << i;
    EXPECT_NEAR(bot.h[i].command, 0.5 / 0.1, 1e-12) << i;
  }
  // Clamped to +-pi/2.
  ASSERT_TRUE(c.setFourWheelSteering(3.0, 3.0, 0.0));
  bot.step(0.02, 0.01);
  EXPECT_NEAR(bot.h[4].command, std::atan(std::tan(M_PI_2)), 1e-9);
  EXPECT_FALSE(c.setFourWheelSteering(0.0, std::nan(""), 1.0));
}

// The newer command drives; older than cmd_vel_timeout, it brakes.
TEST(FourWheelSteeringController, TheLatestCommandDrivesAndATimeoutBrakes) {
  Bot bot;
  ControllerSpec s = spec();
  s.params["cmd_vel_timeout"] = 0.25;
  FourWheelSteeringController& c = bot.load(s);
  c.setFourWheelSteering(0.3, 0.3, 0.5);
  bot.step(0.01, 0.01);
  c.setTwist(1.0, 0.0, 0.0);  // newer: straight at 1 m/s
  bot.step(0.02, 0.01);
  EXPECT_NEAR(bot.h[0].command, 10.0, 1e-12);
  EXPECT_NEAR(bot.h[4].command, 0.0, 1e-12);
  bot.step(0.27, 0.25);  // 0.25 s old: still followed
  EXPECT_NEAR(bot.h[0].command, 10.0, 1e-12);
  bot.step(0.28, 0.01);
  EXPECT_EQ(bot.h[0].command, 0.0);
  EXPECT_EQ(bot.h[4].command, 0.0);
}

// The odometry fed back the controller's own commands (joints that follow exactly) measures
// the commanded motion: speed, yaw rate, and a crab's sideways velocity.
TEST(FourWheelSteeringController, OdometryOfItsOwnCommands) {
  {
    Bot bot;
    FourWheelSteeringController& c = bot.load(spec());
    double t = 0.0;
    for (int k = 0; k < 200; ++k) {  // sent every update (older than cmd_vel_timeout, it brakes)
      c.setFourWheelSteering(0.2, -0.2, 0.5);
      bot.step(t += 0.01, 0.01);
    }
    const double w = 0.5 * (std::tan(0.2) - std::tan(-0.2)) / 1.0;
    // Within 1 %: upstream's odometry is not the exact inverse of its command with a steering
    // offset (its front speed takes the raw wheel speeds): +0.5 % on both here.
    EXPECT_NEAR(c.odometry().angular(), w, 0.01 * w);
    EXPECT_NEAR(c.odometry().linear(), 0.5, 0.005);
    EXPECT_NEAR(c.odometry().linearY(), 0.0, 1e-3);
    EXPECT_NEAR(c.odometry().heading(), w * (t - 0.02), 0.02 * w * t);
    const std::vector<FourWheelSteeringController::OdomSample> out = c.takeOdom();
    ASSERT_FALSE(out.empty());  // at publish_rate (50 Hz)
    EXPECT_NEAR(out.back().front_steering, 0.2, 1e-9);
    EXPECT_NEAR(out.back().rear_steering, -0.2, 1e-9);
  }
  {
    Bot bot;
    FourWheelSteeringController& c = bot.load(spec());
    double t = 0.0;
    for (int k = 0; k < 100; ++k) {
      c.setFourWheelSteering(0.3, 0.3, 0.5);
      bot.step(t += 0.01, 0.01);
    }
    EXPECT_NEAR(c.odometry().angular(), 0.0, 1e-9);
    EXPECT_NEAR(c.odometry().linearX(), 0.5 * std::cos(0.3), 1e-9);
    EXPECT_NEAR(c.odometry().linearY(), 0.5 * std::sin(0.3), 1e-9);
  }
}
