// Wheel odometry against the closed form of a circle.
#include <cmath>

#include <gtest/gtest.h>

#include "tianracer_control/ackermann.h"
#include "tianracer_control/odometry.h"

#include "control_test_support.h"

using namespace tianracer_control;  // NOLINT: test file

namespace {
using test::geometry;
}  // namespace

TEST(Odometry, StraightLine) {
  BicycleOdometry odo(geometry());
  // 10 rad/s * 0.05 m = 0.5 m/s for 2 s along yaw = 0.
  for (int k = 0; k < 200; ++k) ASSERT_TRUE(odo.update(10.0, 10.0, 0.0, 0.0, 0.01));
  EXPECT_NEAR(odo.x(), 1.0, 1e-12);
  EXPECT_NEAR(odo.y(), 0.0, 1e-15);
  EXPECT_NEAR(odo.yaw(), 0.0, 1e-15);
  EXPECT_NEAR(odo.linearVelocity(), 0.5, 1e-15);
  EXPECT_NEAR(odo.distance(), 1.0, 1e-12);
}

TEST(Odometry, KnownArcMatchesTheClosedForm) {
  const AckermannGeometry g = geometry();
  // Exact Ackermann angles for delta = 0.3; v = 0.5 m/s (omega = 10 rad/s, differential).
  const AckermannCommand c = twistToAckermann(g, 0.5, 0.3, test::steeringAngleDifferential());
  const double R = g.wheelbase / std::tan(0.3);  // 0.808183... m, rear axle midpoint
  const double w = 0.5 / R;
  BicycleOdometry odo(g);
  // Coarse steps on purpose: the arc is integrated exactly, whatever dt.
  const double dt = 0.1;
  const int n = 73;
  for (int k = 0; k < n; ++k) {
    ASSERT_TRUE(odo.update(c.left_wheel_omega, c.right_wheel_omega, c.left_steer, c.right_steer, dt));
  }
  const double t = n * dt;
  // Circle of radius R about (0, R): x = R sin(w t), y = R (1 - cos(w t)), yaw = w t.
  EXPECT_NEAR(odo.x(), R * std::sin(w * t), 1e-12);
  EXPECT_NEAR(odo.y(), R * (1.0 - std::cos(w * t)), 1e-12);
  EXPECT_NEAR(odo.yaw(), w * t, 1e-12);
  EXPECT_NEAR(odo.angularVelocity(), w, 1e-12);
  EXPECT_NEAR(odo.distance(), 0.5 * t, 1e-12);
}

TEST(Odometry, BaseFrameAheadOfTheRearAxle) {
  AckermannGeometry g = geometry();
  g.rear_axle_x = -0.125;  // base_link 0.125 m ahead of the rear axle
  BicycleOdometry odo(g);
  odo.reset(0.0, 0.0, 0.0);
  EXPECT_NEAR(odo.x(), 0.0, 1e-15);
  const double R = 1.0, v = 0.5, w = v / R;
  const double dt = 0.02;
  const int n = 314;
  for (int k = 0; k < n; ++k) ASSERT_TRUE(odo.integrate(v, w, dt));
  const double th = w * n * dt;
  // Rear axle on the circle about (0, R) starting at (-0.125, 0); base = axle + 0.125 heading.
  EXPECT_NEAR(odo.x(), -0.125 + R * std::sin(th) + 0.125 * std::cos(th), 1e-12);
  EXPECT_NEAR(odo.y(), R * (1.0 - std::cos(th)) + 0.125 * std::sin(th), 1e-12);
  EXPECT_NEAR(odo.lateralVelocity(), 0.125 * w, 1e-15);
}

TEST(Odometry, PositionsGiveTheSameArc) {
  const AckermannGeometry g = geometry();
  BicycleOdometry by_speed(g), by_position(g);
  const double hinge_l = leftWheelAngle(g, 0.2), hinge_r = rightWheelAngle(g, 0.2);
  double pos = 0.0;
  EXPECT_FALSE(by_position.updateFromPositions(pos, pos, hinge_l, hinge_r, 0.02));  // stores
  for (int k = 0; k < 100; ++k) {
    pos += 8.0 * 0.02;
    by_speed.update(8.0, 8.0, hinge_l, hinge_r, 0.02);
    ASSERT_TRUE(by_position.updateFromPositions(pos, pos, hinge_l, hinge_r, 0.02));
  }
  EXPECT_NEAR(by_position.x(), by_speed.x(), 1e-9);
  EXPECT_NEAR(by_position.y(), by_speed.y(), 1e-9);
  EXPECT_NEAR(by_position.yaw(), by_speed.yaw(), 1e-9);
}

TEST(Odometry, DeterministicAndResettable) {
  BicycleOdometry a(geometry()), b(geometry());
  for (int k = 0; k < 1000; ++k) {
    const double s = std::sin(0.01 * k);
    a.update(5.0 + s, 5.0 - s, 0.3 * s, 0.25 * s, 0.005);
    b.update(5.0 + s, 5.0 - s, 0.3 * s, 0.25 * s, 0.005);
  }
  EXPECT_EQ(a.x(), b.x());
  EXPECT_EQ(a.y(), b.y());
  EXPECT_EQ(a.yaw(), b.yaw());
  a.reset(1.0, 2.0, 0.5);
  EXPECT_DOUBLE_EQ(a.x(), 1.0);
  EXPECT_DOUBLE_EQ(a.y(), 2.0);
  EXPECT_EQ(a.yaw(), 0.5);
  EXPECT_EQ(a.linearVelocity(), 0.0);
  EXPECT_EQ(a.distance(), 0.0);
}

TEST(Odometry, BadInputIsIgnored) {
  BicycleOdometry odo(geometry());
  EXPECT_FALSE(odo.update(1.0, 1.0, 0.0, 0.0, 0.0));
  EXPECT_FALSE(odo.update(NAN, 1.0, 0.0, 0.0, 0.1));
  EXPECT_FALSE(odo.integrate(1.0, INFINITY, 0.1));
  EXPECT_EQ(odo.x(), 0.0);
  EXPECT_EQ(odo.yaw(), 0.0);
}

TEST(Odometry, HeadingWraps) {
  BicycleOdometry odo(geometry());
  odo.integrate(1.0, 1.0, 4.0);  // yaw = 4 rad
  EXPECT_NEAR(odo.heading(), 4.0 - 2.0 * M_PI, 1e-12);
}

TEST(Odometry, WrappedPositionsAreUnwrapped) {
  BicycleOdometry odo(geometry());
  odo.updateFromPositions(3.0, 3.0, 0.0, 0.0, 0.02);
  // 3.0 -> 3.2 published as 3.2 - 2 pi: still +0.2 rad, 0.2 * 0.05 = 0.01 m.
  ASSERT_TRUE(odo.updateFromPositions(3.2 - 2 * M_PI, 3.2 - 2 * M_PI, 0.0, 0.0, 0.02));
  EXPECT_NEAR(odo.x(), 0.01, 1e-12);
}

TEST(Odometry, BaseFrameOffsetBothWaysFromTheRearAxle) {
  // The seed's rear axle midpoint is at (-0.12498, -0.002347) in base_link: base_link is
  // b = (0.12498, 0.002347) from it in the body frame.
  AckermannGeometry g = geometry();
  g.rear_axle_x = -0.12498;
  g.rear_axle_y = -0.002347;
  const double bx = 0.12498, by = 0.002347;
  BicycleOdometry odo(g);
  odo.reset(1.0, 2.0, 0.7);
  EXPECT_NEAR(odo.x(), 1.0, 1e-15);
  EXPECT_NEAR(odo.y(), 2.0, 1e-15);
  // Rear axle at base - Rot(0.7) b; then a quarter circle of R = 1 left about the point R to
  // its left.
  const double c0 = std::cos(0.7), s0 = std::sin(0.7);
  const double px = 1.0 - (c0 * bx - s0 * by), py = 2.0 - (s0 * bx + c0 * by);
  const double cx = px - s0, cy = py + c0;  // centre, R = 1
  const double v = 0.5, w = 0.5;
  for (int k = 0; k < 157; ++k) ASSERT_TRUE(odo.integrate(v, w, 0.02));
  const double th = 0.7 + w * 157 * 0.02;
  const double qx = cx + std::sin(th), qy = cy - std::cos(th);  // rear axle now
  EXPECT_NEAR(odo.x(), qx + std::cos(th) * bx - std::sin(th) * by, 1e-12);
  EXPECT_NEAR(odo.y(), qy + std::sin(th) * bx + std::cos(th) * by, 1e-12);
  // Base velocity in the body frame: (v, 0) + w x b = (v - w by, w bx).
  EXPECT_NEAR(odo.linearVelocity(), v - w * by, 1e-15);
  EXPECT_NEAR(odo.lateralVelocity(), w * bx, 1e-15);
}
