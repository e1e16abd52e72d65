// diff_drive_controller/DiffDriveController without ROS: parameters and their errors (upstream's
// messages), the wheel geometry from the URDF, kinematics, limits, timeout, odometry.
#include <cmath>
#include <limits>
#include <map>
#include <string>
#include <vector>

#include <gtest/gtest.h>
#include <urdf_parser/urdf_parser.h>

#include "tianracer_control/controllers/diff_drive_controller.h"
#include "tianracer_control/joint_controllers.h"

#include "control_test_support.h"

using namespace tianracer_control;  // NOLINT: test file

namespace {

// Wheels 0.05 m in radius, origins (0, +-0.12, 0) in base_link; `wheel` replaces the left
// wheel's collision geometry.
std::string diffbot(const std::string& wheel = "<cylinder radius=\"0.05\" length=\"0.02\"/>") {
  return R"(<robot name="diffbot">
  <link name="base_link"/>
  <link name="left_wheel"><collision><geometry>)" + wheel + R"(</geometry></collision></link>
  <link name="right_wheel"><collision><geometry><cylinder radius="0.05" length="0.02"/></geometry></collision></link>
  <link name="left_rear"/><link name="right_rear"/>
  <joint name="left_wheel_joint" type="continuous"><parent link="base_link"/><child link="left_wheel"/>
    <origin xyz="0 0.12 0"/><axis xyz="0 1 0"/></joint>
  <joint name="right_wheel_joint" type="continuous"><parent link="base_link"/><child link="right_wheel"/>
    <origin xyz="0 -0.12 0"/><axis xyz="0 1 0"/></joint>
  <joint name="left_rear_joint" type="continuous"><parent link="base_link"/><child link="left_rear"/>
    <origin xyz="-0.2 0.12 0"/><axis xyz="0 1 0"/></joint>
  <joint name="right_rear_joint" type="continuous"><parent link="base_link"/><child link="right_rear"/>
    <origin xyz="-0.2 -0.12 0"/><axis xyz="0 1 0"/></joint>
</robot>)";
}

struct Bot {
  JointHandle left, right, left_rear, right_rear, effort;
  std::map<std::string, JointHandle*> joints;
  urdf::ModelInterfaceSharedPtr urdf;
  ControllerSet set;

  explicit Bot(const std::string& xml = diffbot()) : urdf(urdf::parseURDF(xml)) {
    left.name = "left_wheel_joint";
    right.name = "right_wheel_joint";
    left_rear.name = "left_rear_joint";
    right_rear.name = "right_rear_joint";
    effort.name = "effort_joint";
    for (JointHandle* h : {&left, &right, &left_rear, &right_rear}) {
      h->interface = JointHandle::Interface::kVelocity;
      h->continuous = true;
      joints[h->name] = h;
    }
    joints[effort.name] = &effort;
    set.setRobotDescription(urdf.get());
  }
  DiffDriveController& load(const ControllerSpec& s) {
    return dynamic_cast<DiffDriveController&>(set.load(s, joints));
  }
  std::string errorOf(const ControllerSpec& s) {
    try {
      builtinControllers().create(s, joints, WarningSink(), urdf.get());
    } catch (const ControllerError& e) {
      return e.what();
    }
    return "";
  }
  /// The wheels turn as commanded for dt (no slip), then the controllers update at time t.
  void step(double t, double dt) {
    for (JointHandle* h : {&left, &right, &left_rear, &right_rear}) {
      h->position += h->command * dt;
      h->velocity = h->command;
    }
    set.update(dt, t);
  }
};

ControllerSpec ddSpec() {
  ControllerSpec s = test::spec("dd", DiffDriveController::kType, "");
  s.params["left_wheel"] = "left_wheel_joint";
  s.params["right_wheel"] = "right_wheel_joint";
  return s;
}

ParamValue list(const std::vector<ParamValue>& items) { return ParamValue::list(items); }

}  // namespace

TEST(DiffDriveController, WheelGeometryFromTheUrdfAndItsMultipliers) {
  Bot bot;
  DiffDriveController& dd = bot.load(ddSpec());
  EXPECT_DOUBLE_EQ(dd.params().wheel_separation, 0.24);  // |origin left - origin right|
  EXPECT_DOUBLE_EQ(dd.params().wheel_radius, 0.05);      // the left wheel's cylinder
  EXPECT_EQ(dd.claimedJoints(), (std::vector<const JointHandle*>{&bot.left, &bot.right}));

  Bot sphere(diffbot("<sphere radius=\"0.07\"/>"));
  EXPECT_DOUBLE_EQ(sphere.load(ddSpec()).params().wheel_radius, 0.07);

  Bot given;
  ControllerSpec s = ddSpec();
  s.params["wheel_separation"] = 0.5;
  s.params["wheel_radius"] = 0.1;
  s.params["wheel_separation_multiplier"] = 2.0;
  s.params["left_wheel_radius_multiplier"] = 0.5;  // both overridden by wheel_radius_multiplier
  s.params["wheel_radius_multiplier"] = 1.5;
  DiffDriveController& g = given.load(s);
  EXPECT_DOUBLE_EQ(g.wheelSeparation(), 1.0);
  EXPECT_DOUBLE_EQ(g.leftWheelRadius(), 0.15);
  EXPECT_DOUBLE_EQ(g.rightWheelRadius(), 0.15);
  // Given both, no robot_description is needed.
  Bot none;
  none.set.setRobotDescription(nullptr);
  EXPECT_DOUBLE_EQ(none.load(s).wheelSeparation(), 1.0);
}

TEST(DiffDriveController, WheelVelocitiesFromTheCommand) {
  Bot bot;
  DiffDriveController& dd = bot.load(ddSpec());
  EXPECT_TRUE(dd.setCommand(0.5, 1.0));
  bot.step(0.01, 0.01);
  EXPECT_DOUBLE_EQ(bot.left.command, (0.5 - 1.0 * 0.24 / 2) / 0.05);
  EXPECT_DOUBLE_EQ(bot.right.command, (0.5 + 1.0 * 0.24 / 2) / 0.05);
  // NaN: ignored, the last command stays.
  EXPECT_FALSE(dd.setCommand(std::numeric_limits<double>::quiet_NaN(), 0.0));
  EXPECT_FALSE(dd.setCommand(0.0, std::numeric_limits<double>::infinity()));
  bot.step(0.02, 0.01);
  EXPECT_DOUBLE_EQ(bot.right.command, (0.5 + 1.0 * 0.24 / 2) / 0.05);
}

TEST(DiffDriveController, SkidSteerCommandsEveryWheelAndAveragesEachSide) {
  Bot bot;
  ControllerSpec s = ddSpec();
  s.params["left_wheel"] = list({"left_wheel_joint", "left_rear_joint"});
  s.params["right_wheel"] = list({"right_wheel_joint", "right_rear_joint"});
  DiffDriveController& dd = bot.load(s);
  EXPECT_EQ(dd.claimedJoints().size(), 4u);
  dd.setCommand(0.2, 0.0);
  bot.step(0.01, 0.01);
  for (const JointHandle* h : {&bot.left, &bot.right, &bot.left_rear, &bot.right_rear}) {
    EXPECT_DOUBLE_EQ(h->command, 4.0) << h->name;
  }
  // One side's mean position: one wheel 0.1 rad ahead, the other 0.1 behind: no turn.
  bot.left.position += 0.1;
  bot.left_rear.position -= 0.1;
  bot.set.update(0.01, 0.03);
  EXPECT_NEAR(dd.odometry().heading(), 0.0, 1e-12);
}

TEST(DiffDriveController, StopsWhenTheCommandIsOlderThanTheTimeout) {
  Bot bot;
  ControllerSpec s = ddSpec();
  s.params["cmd_vel_timeout"] = 0.25;
  DiffDriveController& dd = bot.load(s);
  const double dt = 1.0 / 64;  // exact in binary: the ages below are exact
  dd.setCommand(0.5, 0.0);     // stamped at the next update, t = dt
  double t = 0.0;
  for (int i = 0; i < 17; ++i) bot.step(t += dt, dt);  // 0.25 s old: still followed
  EXPECT_DOUBLE_EQ(bot.left.command, 10.0);
  bot.step(t += dt, dt);  // older than 0.25 s
  EXPECT_EQ(bot.left.command, 0.0);
  EXPECT_EQ(bot.right.command, 0.0);
  dd.setCommand(0.5, 0.0);  // a new one moves it again
  bot.step(t += dt, dt);
  EXPECT_DOUBLE_EQ(bot.left.command, 10.0);
}

TEST(DiffDriveController, VelocityAccelerationAndJerkLimits) {
  Bot bot;
  ControllerSpec s = ddSpec();
  s.params["linear"]["x"]["has_velocity_limits"] = true;
  s.params["linear"]["x"]["max_velocity"] = 1.0;  // min: -1
  s.params["linear"]["x"]["has_acceleration_limits"] = true;
  s.params["linear"]["x"]["max_acceleration"] = 2.0;
  s.params["linear"]["x"]["min_acceleration"] = -4.0;
  s.params["angular"]["z"]["has_velocity_limits"] = true;
  s.params["angular"]["z"]["max_velocity"] = 0.5;
  s.params["angular"]["z"]["min_velocity"] = -0.1;
  s.params["publish_cmd"] = true;
  s.params["cmd_vel_timeout"] = 100.0;
  DiffDriveController& dd = bot.load(s);
  dd.setCommand(5.0, -3.0);
  double t = 0.0;
  bot.step(t += 0.1, 0.1);
  EXPECT_NEAR(dd.lastLinear(), 0.2, 1e-12);  // 2 m/s^2 for 0.1 s
  EXPECT_DOUBLE_EQ(dd.lastAngular(), -0.1);
  for (int i = 0; i < 10; ++i) bot.step(t += 0.1, 0.1);
  EXPECT_DOUBLE_EQ(dd.lastLinear(), 1.0);  // max_velocity
  dd.setCommand(-1.0, 0.0);
  bot.step(t += 0.1, 0.1);
  EXPECT_NEAR(dd.lastLinear(), 0.6, 1e-12);  // -4 m/s^2
  // cmd_vel_out: the limited commands, one per update.
  const std::vector<CmdVelDriveController::CmdSample> out = dd.takeCmdOut();
  ASSERT_EQ(out.size(), 12u);
  EXPECT_NEAR(out.front().linear, 0.2, 1e-12);
  EXPECT_NEAR(out.back().linear, 0.6, 1e-12);
  EXPECT_TRUE(dd.takeCmdOut().empty());

  SpeedLimiter jerk;
  jerk.has_jerk_limits = true;
  jerk.max_jerk = 10.0;
  jerk.min_jerk = -10.0;
  double v = 1.0;
  jerk.limit(v, 0.0, 0.0, 0.1);  // da limited to 10 * 2 * 0.01 = 0.2
  EXPECT_NEAR(v, 0.2, 1e-12);
}

// An outbox nobody takes (a host without ROS) keeps the latest 100 publications.
TEST(DiffDriveController, AnOutboxNobodyTakesKeepsTheLatestHundred) {
  Bot bot;
  ControllerSpec s = ddSpec();
  s.params["publish_cmd"] = true;
  s.params["cmd_vel_timeout"] = 100.0;
  DiffDriveController& dd = bot.load(s);
  dd.setCommand(0.1, 0.0);
  for (int i = 1; i <= 150; ++i) bot.step(i * 0.01, 0.01);
  const std::vector<CmdVelDriveController::CmdSample> out = dd.takeCmdOut();
  ASSERT_EQ(out.size(), 100u);
  EXPECT_DOUBLE_EQ(out.front().t, 0.51);  // updates 51..150
  EXPECT_DOUBLE_EQ(out.back().t, 1.5);
  EXPECT_TRUE(dd.takeCmdOut().empty());
}

TEST(Outbox, TakeEmptiesClearDropsPostBeyondTheLimitDropsTheOldest) {
  Outbox<int> box;
  for (int i = 0; i < 3; ++i) box.post(i);
  EXPECT_EQ(box.take(), (std::vector<int>{0, 1, 2}));
  EXPECT_EQ(box.size(), 0u);
  box.post(7);
  box.clear();
  EXPECT_TRUE(box.take().empty());
  for (int i = 0; i < static_cast<int>(Outbox<int>::kLimit) + 5; ++i) box.post(i);
  const std::vector<int> kept = box.take();
  ASSERT_EQ(kept.size(), Outbox<int>::kLimit);
  EXPECT_EQ(kept.front(), 5);
  EXPECT_EQ(kept.back(), static_cast<int>(Outbox<int>::kLimit) + 4);
}

TEST(DiffDriveController, OdometryFromTheWheelsAtThePublishRate) {
  Bot bot;
  ControllerSpec s = ddSpec();
  s.params["publish_rate"] = 16.0;  // a period of 1/16 s, exact in binary as the steps
  s.params["cmd_vel_timeout"] = 100.0;
  s.params["pose_covariance_diagonal"] = list({0.001, 0.001, 1000000.0, 1000000.0, 1000000.0, 1000.0});
  s.params["enable_odom_tf"] = false;
  DiffDriveController& dd = bot.load(s);
  EXPECT_EQ(dd.common().pose_covariance_diagonal[5], 1000.0);
  EXPECT_EQ(dd.common().twist_covariance_diagonal[0], 0.0);  // absent: zeros, as upstream
  const double v = 0.4, w = 0.5;
  dd.setCommand(v, w);
  double t = 0.0;
  const double dt = 1.0 / 256;
  for (int i = 0; i < 256; ++i) bot.step(t += dt, dt);  // 1 s
  // The wheels followed the command from the first update on (one update's delay).
  const double travelled = 1.0 - dt;
  EXPECT_NEAR(dd.odometry().heading(), w * travelled, 1e-9);
  EXPECT_NEAR(dd.odometry().x(), v / w * std::sin(w * travelled), 1e-9);
  EXPECT_NEAR(dd.odometry().y(), v / w * (1.0 - std::cos(w * travelled)), 1e-9);
  EXPECT_NEAR(dd.odometry().linear(), v, 1e-9);
  EXPECT_NEAR(dd.odometry().angular(), w, 1e-9);
  const std::vector<CmdVelDriveController::OdomSample> odom = dd.takeOdom();
  EXPECT_EQ(odom.size(), 15u);  // at the first update after each k/16 s, k = 1..15 (t <= 1)
  EXPECT_DOUBLE_EQ(odom.front().t, 1.0 / 16 + dt);
  EXPECT_FALSE(odom.back().tf);

  // Open loop: the limited commands integrated, whatever the wheels do.
  Bot open;
  ControllerSpec o = ddSpec();
  o.params["open_loop"] = true;
  DiffDriveController& ol = open.load(o);
  ol.setCommand(1.0, 0.0);
  open.step(0.1, 0.1);  // integrates the previous command (0) over 0.1 s
  open.left.position = open.right.position = 1000.0;
  open.step(0.2, 0.1);
  EXPECT_NEAR(ol.odometry().x(), 0.1, 1e-12);
  // A sim reset starts the odometry again at 0.
  ol.reset();
  EXPECT_EQ(ol.odometry().x(), 0.0);
}

TEST(DiffDriveController, ConfigurationErrorsAreUpstreams) {
  Bot bot;
  const std::string pre = "controller 'dd': ";
  ControllerSpec s = ddSpec();
  s.params.erase("left_wheel");
  EXPECT_EQ(bot.errorOf(s), pre + "Couldn't retrieve wheel param 'left_wheel'.");
  s = ddSpec();
  s.params["right_wheel"] = 3;
  EXPECT_EQ(bot.errorOf(s), pre + "Wheel param 'right_wheel' is neither a list of strings nor a string.");
  s.params["right_wheel"] = list({"right_wheel_joint", 2});
  EXPECT_EQ(bot.errorOf(s), pre + "Wheel param 'right_wheel' #1 isn't a string.");
  s.params["right_wheel"] = list({});
  EXPECT_EQ(bot.errorOf(s), pre + "Wheel param 'right_wheel' is an empty list");
  s.params["right_wheel"] = list({"right_wheel_joint", "right_rear_joint"});
  EXPECT_EQ(bot.errorOf(s), pre + "#left wheels (1) != #right wheels (2).");

  // The geometry from the URDF.
  s = ddSpec();
  s.params["left_wheel"] = "nowhere_joint";
  EXPECT_EQ(bot.errorOf(s), pre + "nowhere_joint couldn't be retrieved from model description");
  Bot box(diffbot("<box size=\"0.1 0.1 0.1\"/>"));
  EXPECT_EQ(box.errorOf(ddSpec()),
            pre + "Wheel link left_wheel is NOT modeled as a cylinder or sphere!\n" + pre +
                "Couldn't retrieve left_wheel_joint wheel radius");
  s = ddSpec();
  s.params["wheel_radius"] = 0.05;  // the separation is still looked up
  try {
    builtinControllers().create(s, bot.joints);  // no robot_description
    ADD_FAILURE();
  } catch (const ControllerError& e) {
    EXPECT_EQ(std::string(e.what()), pre + "Robot description couldn't be retrieved from param server.");
  }
  s.params["wheel_radius"] = -0.05;
  s.params["wheel_separation"] = 0.3;
  EXPECT_EQ(bot.errorOf(s), pre + "wheel_radius must be positive, got -0.05");

  // Kinds and values.
  s = ddSpec();
  s.params["publish_rate"] = "fast";
  EXPECT_EQ(bot.errorOf(s), pre + "publish_rate must be a number, got a string");
  s = ddSpec();
  s.params["open_loop"] = 1;
  EXPECT_EQ(bot.errorOf(s), pre + "open_loop must be true or false, got an int");
  s = ddSpec();
  s.params["linear"]["x"]["max_velocity"] = "1";
  EXPECT_EQ(bot.errorOf(s), pre + "linear/x/max_velocity must be a number, got a string");
  s = ddSpec();
  s.params["twist_covariance_diagonal"] = list({0.1, 0.1, 0.1, 0.1, 0.1});
  EXPECT_EQ(bot.errorOf(s), pre + "twist_covariance_diagonal must be a list of 6 numbers, got a list of 5");
  s = ddSpec();
  s.params["velocity_rolling_window_size"] = 0;
  EXPECT_EQ(bot.errorOf(s), pre + "velocity_rolling_window_size must be a positive integer, got 0");

  // The wheels need velocity transmissions.
  s = ddSpec();
  s.params["right_wheel"] = "effort_joint";
  s.params["wheel_separation"] = 0.3;
  s.params["wheel_radius"] = 0.05;
  const std::string e = bot.errorOf(s);
  EXPECT_NE(e.find("needs the velocity interface (VelocityJointInterface) but the transmission "
                   "of joint 'effort_joint' gives the effort interface"),
            std::string::npos)
      << e;
}

TEST(DiffDriveController, ItsUnknownKeysAreWarnedAndItsOwnAreNot) {
  Bot bot;
  ControllerSpec s = ddSpec();
  for (const char* key : {"publish_rate", "cmd_vel_timeout", "wheel_separation", "wheel_radius"})
    s.params[key] = 1.0;
  s.params["base_frame_id"] = "base_footprint";
  s.params["linear"]["x"]["has_jerk_limits"] = false;
  s.params["wheel_radious"] = 0.1;  // a typo
  std::vector<std::string> warnings;
  builtinControllers().create(s, bot.joints, [&](const std::string& w) { warnings.push_back(w); },
                              bot.urdf.get());
  EXPECT_EQ(warnings, (std::vector<std::string>{
                          "controller 'dd': key 'wheel_radious' is not used by "
                          "diff_drive_controller/DiffDriveController, ignored"}));
}

// publish_wheel_joint_controller_state: upstream's publishWheelData() every update, left wheels
// then right, term for term (its desired acceleration is (v - v_prev) * dt, and with several
// wheels a side every pair after the first reports 0: it saves "previous" inside the loop).
TEST(DiffDriveController, WheelJointControllerStateAsUpstreamFillsIt) {
  {
    Bot bot;
    DiffDriveController& dd = bot.load(ddSpec());  // off by default
    dd.setCommand(0.5, 1.0);
    bot.step(0.01, 0.01);
    EXPECT_TRUE(dd.takeWheelStates().empty());
  }
  Bot bot;
  ControllerSpec s = ddSpec();
  s.params["left_wheel"] = list({"left_wheel_joint", "left_rear_joint"});
  s.params["right_wheel"] = list({"right_wheel_joint", "right_rear_joint"});
  s.params["publish_wheel_joint_controller_state"] = true;
  DiffDriveController& dd = bot.load(s);
  EXPECT_EQ(dd.wheelJointNames(),
            (std::vector<std::string>{"left_wheel_joint", "left_rear_joint", "right_wheel_joint", "right_rear_joint"}));
  dd.setCommand(0.5, 1.0);
  bot.step(0.01, 0.01);
  bot.step(0.02, 0.01);
  const std::vector<DiffDriveController::WheelState> states = dd.takeWheelStates();
  ASSERT_EQ(states.size(), 2u);
  const DiffDriveController::WheelState& w = states[1];
  EXPECT_DOUBLE_EQ(w.t, 0.02);
  const double vl = (0.5 - 1.0 * 0.24 / 2) / 0.05, vr = (0.5 + 1.0 * 0.24 / 2) / 0.05;
  const std::vector<double> v_desired{vl, vl, vr, vr};
  for (std::size_t k = 0; k < 4; ++k) {
    EXPECT_DOUBLE_EQ(w.desired.velocities[k], v_desired[k]) << k;
    EXPECT_NEAR(w.desired.positions[k], 2 * v_desired[k] * 0.01, 1e-12) << k;  // integrated over two updates
    EXPECT_EQ(w.desired.accelerations[k], 0.0) << k;  // the command did not change
    EXPECT_TRUE(std::isnan(w.desired.effort[k]));
    EXPECT_TRUE(std::isnan(w.error.effort[k]));
    // Actual: the wheels turned at the first update's command for 0.01 s.
    EXPECT_DOUBLE_EQ(w.actual.velocities[k], v_desired[k]) << k;
    EXPECT_NEAR(w.actual.accelerations[k], v_desired[k] / 0.01, 1e-9) << k;
    EXPECT_NEAR(w.error.positions[k], w.desired.positions[k] - w.actual.positions[k], 1e-15);
    EXPECT_NEAR(w.error.velocities[k], 0.0, 1e-12);
  }
  // The first update: the front pair's desired acceleration (v - 0) * dt, the rear pair's 0.
  EXPECT_NEAR(states[0].desired.accelerations[0], vl * 0.01, 1e-12);
  EXPECT_NEAR(states[0].desired.accelerations[2], vr * 0.01, 1e-12);
  EXPECT_EQ(states[0].desired.accelerations[1], 0.0);
  EXPECT_EQ(states[0].desired.accelerations[3], 0.0);
}
