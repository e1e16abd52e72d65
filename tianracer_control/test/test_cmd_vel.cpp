// The cmd_vel node's logic: limits, timeout, ramp, bad input, time jumps.
#include <cmath>
#include <limits>

#include <gtest/gtest.h>

#include "tianracer_control/cmd_vel.h"

#include "control_test_support.h"

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

// --- Ackermann drive commands (ackermann_msgs/AckermannDrive) ---------------------------

namespace {
AckermannDriveInput drive(double speed, double angle, double angle_rate = 0.0,
                          double accel = 0.0) {
  AckermannDriveInput d;
  d.speed = speed;
  d.steering_angle = angle;
  d.steering_angle_velocity = angle_rate;
  d.acceleration = accel;
  return d;
}
}  // namespace

TEST(CmdVelAckermann, SpeedAndAngleToWheels) {
  CmdVelProcessor p(geometry(), AckermannOptions(), CmdVelLimits());
  const AckermannDriveResult r = p.setAckermann(drive(1.0, 0.3), 1.0);
  EXPECT_FALSE(r.rejected || r.speed_clamped || r.steering_clamped);
  const AckermannCommand c = p.update(1.02);
  EXPECT_NEAR(c.delta, 0.3, 1e-12);                   // the bicycle angle itself
  EXPECT_NEAR(c.left_steer, 0.3265457065, 1e-9);      // as in steering-angle mode
  EXPECT_NEAR(c.left_wheel_omega, 20.0, 1e-12);       // v / r
  EXPECT_NEAR(c.yaw_rate, std::tan(0.3) / 0.25, 1e-12);  // radius L / tan(0.3)
}

TEST(CmdVelAckermann, SteeringAngleVelocityLimitsTheSteeringRate) {
  CmdVelLimits limits;
  limits.cmd_timeout = 0.0;
  CmdVelProcessor p(geometry(), AckermannOptions(), limits);
  p.update(0.0);
  p.setAckermann(drive(0.5, 0.4, 1.0), 0.0);  // 1 rad/s toward 0.4 rad
  EXPECT_NEAR(p.update(0.1).delta, 0.1, 1e-12);
  EXPECT_NEAR(p.update(0.2).delta, 0.2, 1e-12);
  EXPECT_NEAR(p.update(1.0).delta, 0.4, 1e-12);  // reached, held
  // Negative rates are magnitudes too; back toward -0.2 at 2 rad/s.
  p.setAckermann(drive(0.5, -0.2, -2.0), 1.0);
  EXPECT_NEAR(p.update(1.1).delta, 0.2, 1e-12);
  EXPECT_NEAR(p.update(1.5).delta, -0.2, 1e-12);
  // Zero: steer at once.
  p.setAckermann(drive(0.5, 0.25, 0.0), 1.5);
  EXPECT_NEAR(p.update(1.52).delta, 0.25, 1e-12);
}

TEST(CmdVelAckermann, AccelerationLimitsTheSpeedRamp) {
  CmdVelLimits limits;
  limits.cmd_timeout = 0.0;
  CmdVelProcessor p(geometry(), AckermannOptions(), limits);
  p.update(0.0);
  p.setAckermann(drive(1.0, 0.0, 0.0, 2.0), 0.0);
  EXPECT_NEAR(p.update(0.1).speed, 0.2, 1e-12);
  EXPECT_NEAR(p.update(0.6).speed, 1.0, 1e-12);
  // The node's max_accel still applies: the smaller of the two wins.
  limits.max_accel = 0.5;
  CmdVelProcessor q(geometry(), AckermannOptions(), limits);
  q.update(0.0);
  q.setAckermann(drive(1.0, 0.0, 0.0, 2.0), 0.0);
  EXPECT_NEAR(q.update(0.1).speed, 0.05, 1e-12);
  q.setAckermann(drive(1.0, 0.0, 0.0, 0.1), 0.1);
  EXPECT_NEAR(q.update(0.2).speed, 0.06, 1e-12);
}

TEST(CmdVelAckermann, TimeoutStopsAndHoldsTheSteering) {
  CmdVelLimits limits;
  limits.cmd_timeout = 0.5;
  CmdVelProcessor p(geometry(), AckermannOptions(), limits);
  p.setAckermann(drive(1.0, 0.3), 0.0);
  const AckermannCommand before = p.update(0.5);
  EXPECT_NEAR(before.speed, 1.0, 1e-12);
  const AckermannCommand after = p.update(0.52);
  EXPECT_TRUE(p.timedOut());
  EXPECT_EQ(after.speed, 0.0);
  EXPECT_EQ(after.left_steer, before.left_steer);
}

TEST(CmdVelAckermann, NonFiniteValuesAreRejected) {
  CmdVelProcessor p(geometry(), AckermannOptions(), CmdVelLimits());
  p.setAckermann(drive(0.5, 0.1), 0.0);
  const double nan = std::numeric_limits<double>::quiet_NaN();
  const double inf = std::numeric_limits<double>::infinity();
  EXPECT_TRUE(p.setAckermann(drive(nan, 0.0), 0.1).rejected);
  EXPECT_TRUE(p.setAckermann(drive(0.0, inf), 0.1).rejected);
  EXPECT_TRUE(p.setAckermann(drive(-inf, 0.0), 0.1).rejected);
  EXPECT_TRUE(p.setAckermann(drive(0.0, 0.0, nan), 0.1).rejected);
  EXPECT_TRUE(p.setAckermann(drive(0.0, 0.0, 0.0, inf), 0.1).rejected);
  const AckermannCommand c = p.update(0.2);  // the previous command stays
  EXPECT_NEAR(c.speed, 0.5, 1e-12);
  EXPECT_NEAR(c.delta, 0.1, 1e-12);
  EXPECT_TRUE(std::isfinite(c.left_steer) && std::isfinite(c.left_wheel_omega));
}

TEST(CmdVelAckermann, HugeValuesAreClamped) {
  CmdVelLimits limits;
  limits.max_speed = 2.0;
  CmdVelProcessor p(geometry(), AckermannOptions(), limits);
  p.update(0.0);
  // Rate limits of 1e30 are no limits: the targets are reached in the first tick.
  const AckermannDriveResult r = p.setAckermann(drive(1e30, 1e30, 1e30, 1e30), 0.0);
  EXPECT_FALSE(r.rejected);
  EXPECT_TRUE(r.speed_clamped);
  EXPECT_TRUE(r.steering_clamped);
  const AckermannCommand c = p.update(0.02);
  EXPECT_NEAR(c.speed, 2.0, 1e-12);
  EXPECT_NEAR(c.delta, maxBicycleAngleLeft(geometry()), 1e-12);
  EXPECT_NEAR(c.left_steer, 0.6, 1e-12);  // the inner wheel at its joint limit
  // The steering comes back from the limit at once, not from 1e30.
  p.setAckermann(drive(1.0, -1e30, 1.0), 0.02);
  EXPECT_NEAR(p.update(0.04).delta, maxBicycleAngleLeft(geometry()) - 0.02, 1e-12);
  EXPECT_NEAR(p.update(10.0).delta, -maxBicycleAngleRight(geometry()), 1e-12);
  EXPECT_NEAR(p.update(10.02).right_steer, -0.6, 1e-12);
}

TEST(CmdVelAckermann, LatestOfTwistAndAckermannWins) {
  CmdVelLimits limits;
  limits.cmd_timeout = 0.5;
  CmdVelProcessor p(geometry(), AckermannOptions(), limits);
  p.setTwist(0.5, 0.0, 0.0);
  EXPECT_FALSE(p.twoSourcesActive(0.0));
  p.setAckermann(drive(1.0, 0.2, 1.0), 0.1);
  EXPECT_TRUE(p.twoSourcesActive(0.1));
  EXPECT_NEAR(p.update(0.12).speed, 1.0, 1e-12);
  // A Twist afterwards steers at once (no rate limit of the Ackermann command left over).
  p.setTwist(0.3, 0.0, 0.2);
  const AckermannCommand c = p.update(0.22);
  EXPECT_NEAR(c.speed, 0.3, 1e-12);
  EXPECT_NEAR(c.delta, 0.0, 1e-12);
  // Once the Ackermann source has been silent for the timeout only one is active.
  EXPECT_FALSE(p.twoSourcesActive(0.7));
}
