// The cmd_vel node's logic: limits, timeout, ramp, bad input, time jumps.
#include <cmath>
#include <limits>

#include <gtest/gtest.h>

#include "tianracer_control/cmd_vel.h"

#include "test_geometry.h"

using namespace tianracer_control;  // NOLINT: test file

namespace {
using test::geometry;
using Input = CmdVelProcessor::Input;
}  // namespace

TEST(CmdVel, NothingBeforeTheFirstTwist) {
  CmdVelProcessor p(geometry(), AckermannOptions(), CmdVelLimits());
  const AckermannCommand c = p.update(10.0);
  EXPECT_EQ(c.left_wheel_omega, 0.0);
  EXPECT_EQ(c.left_steer, 0.0);
  EXPECT_FALSE(p.timedOut());
}

TEST(CmdVel, YawRateTwistToWheels) {
  CmdVelProcessor p(geometry(), AckermannOptions(), CmdVelLimits());
  EXPECT_EQ(p.setTwist(0.5, 0.5, 1.0), Input::kAccepted);
  const AckermannCommand c = p.update(1.02);
  EXPECT_NEAR(c.delta, std::atan(0.25), 1e-12);  // atan(L w / v) = atan(0.25)
  EXPECT_NEAR(c.left_wheel_omega, 10.0, 1e-12);
  EXPECT_NEAR(c.yaw_rate, 0.5, 1e-12);
}

TEST(CmdVel, TimeoutStopsAndHoldsTheSteering) {
  CmdVelLimits limits;
  limits.cmd_timeout = 0.5;
  CmdVelProcessor p(geometry(), AckermannOptions(), limits);
  p.setTwist(1.0, 1.0, 0.0);
  const AckermannCommand before = p.update(0.5);  // exactly at the timeout: still driving
  EXPECT_NEAR(before.left_wheel_omega, 20.0, 1e-12);
  EXPECT_FALSE(p.timedOut());
  const AckermannCommand after = p.update(0.52);
  EXPECT_TRUE(p.timedOut());
  EXPECT_EQ(after.left_wheel_omega, 0.0);
  EXPECT_EQ(after.right_wheel_omega, 0.0);
  EXPECT_EQ(after.left_steer, before.left_steer);
  EXPECT_EQ(after.right_steer, before.right_steer);
  // A new Twist drives again.
  p.setTwist(0.3, 0.0, 0.6);
  EXPECT_NEAR(p.update(0.62).left_wheel_omega, 6.0, 1e-12);
  EXPECT_FALSE(p.timedOut());
}

TEST(CmdVel, NonFiniteTwistIsIgnored) {
  CmdVelProcessor p(geometry(), AckermannOptions(), CmdVelLimits());
  p.setTwist(0.5, 0.0, 0.0);
  const double nan = std::numeric_limits<double>::quiet_NaN();
  const double inf = std::numeric_limits<double>::infinity();
  EXPECT_EQ(p.setTwist(nan, 0.0, 0.1), Input::kRejected);
  EXPECT_EQ(p.setTwist(0.0, inf, 0.1), Input::kRejected);
  EXPECT_EQ(p.setTwist(-inf, 0.0, 0.1), Input::kRejected);
  const AckermannCommand c = p.update(0.2);
  EXPECT_NEAR(c.left_wheel_omega, 10.0, 1e-12);  // the previous command stays
}

TEST(CmdVel, HugeValuesAreClamped) {
  CmdVelLimits limits;
  limits.max_speed = 2.0;
  CmdVelProcessor p(geometry(), AckermannOptions(), limits);
  EXPECT_EQ(p.setTwist(1e9, 1e9, 0.0), Input::kSpeedClamped);
  const AckermannCommand c = p.update(0.02);
  EXPECT_NEAR(c.speed, 2.0, 1e-12);
  EXPECT_NEAR(c.left_wheel_omega, 40.0, 1e-12);
  EXPECT_TRUE(c.clamped);
  EXPECT_LE(std::abs(c.left_steer), 0.6);
  EXPECT_LE(std::abs(c.right_steer), 0.6);
  EXPECT_EQ(p.setTwist(-1e9, 0.0, 0.1), Input::kSpeedClamped);
  EXPECT_NEAR(p.update(0.12).speed, -2.0, 1e-12);
}

TEST(CmdVel, AccelerationRampKeepsTheCurvature) {
  CmdVelLimits limits;
  limits.max_accel = 1.0;
  limits.cmd_timeout = 0.0;  // never: this test sends one Twist
  CmdVelProcessor p(geometry(), AckermannOptions(), limits);
  p.update(0.0);
  p.setTwist(1.0, 1.0, 0.0);
  const AckermannCommand c1 = p.update(0.1);
  EXPECT_NEAR(c1.speed, 0.1, 1e-12);
  EXPECT_NEAR(c1.delta, std::atan(0.25), 1e-12);  // from the target v = 1, w = 1
  EXPECT_NEAR(c1.yaw_rate, 0.1, 1e-12);           // curvature 1 / m at 0.1 m/s
  EXPECT_NEAR(p.update(0.5).speed, 0.5, 1e-12);
  EXPECT_NEAR(p.update(2.0).speed, 1.0, 1e-12);
}

TEST(CmdVel, SteeringAngleMode) {
  AckermannOptions o;
  o.angular_z_is_steering_angle = true;
  CmdVelProcessor p(geometry(), o, CmdVelLimits());
  p.setTwist(0.0, 0.3, 0.0);
  const AckermannCommand c = p.update(0.02);
  EXPECT_NEAR(c.left_steer, 0.3265457065, 1e-9);  // see test_ackermann.cpp
  EXPECT_EQ(c.left_wheel_omega, 0.0);
}

TEST(CmdVel, TimeGoingBackwardsResets) {
  CmdVelProcessor p(geometry(), AckermannOptions(), CmdVelLimits());
  p.setTwist(1.0, 0.0, 100.0);
  EXPECT_NEAR(p.update(100.02).speed, 1.0, 1e-12);
  const AckermannCommand c = p.update(0.0);  // sim reset
  EXPECT_EQ(c.speed, 0.0);
  EXPECT_FALSE(p.timedOut());
}
