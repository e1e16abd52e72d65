// joint_limits_interface's saturation maths (tianracer_control/joint_limits.h) against
// hand-computed values.
#include <gtest/gtest.h>

#include "tianracer_control/joint_limits.h"

using tianracer_control::enforceEffortSaturation;
using tianracer_control::JointLimits;
using tianracer_control::PositionSaturation;
using tianracer_control::VelocitySaturation;

namespace {
JointLimits finger() {  // arm_control.urdf's finger: 0 to 0.08 m, 0.5 m/s, 20 N
  JointLimits l;
  l.has_position_limits = true;
  l.min_position = 0.0;
  l.max_position = 0.08;
  l.has_velocity_limits = true;
  l.max_velocity = 0.5;
  l.has_effort_limits = true;
  l.max_effort = 20.0;
  return l;
}
}  // namespace

TEST(PositionSaturation, ClampsToThePositionLimits) {
  JointLimits l = finger();
  l.has_velocity_limits = false;
  PositionSaturation s(l);
  EXPECT_DOUBLE_EQ(s.enforce(0.2, 0.03, 0.001), 0.08);
  EXPECT_DOUBLE_EQ(s.enforce(-1.0, 0.03, 0.001), 0.0);
  EXPECT_DOUBLE_EQ(s.enforce(0.05, 0.03, 0.001), 0.05);
}

TEST(PositionSaturation, StepsAtMostMaxVelocityTimesPeriodFromThePreviousCommand) {
  PositionSaturation s(finger());
  // first: from the joint's position 0.03, 0.5 m/s * 0.01 s = 0.005
  EXPECT_DOUBLE_EQ(s.enforce(0.2, 0.03, 0.01), 0.035);
  // then from the previous command, whatever the position
  EXPECT_DOUBLE_EQ(s.enforce(0.2, 0.0, 0.01), 0.04);
  EXPECT_DOUBLE_EQ(s.enforce(0.0, 0.0, 0.002), 0.039);
  s.reset();
  EXPECT_DOUBLE_EQ(s.enforce(0.0, 0.0795, 0.01), 0.0745);
  // the position limit still bounds the step
  s.reset();
  EXPECT_DOUBLE_EQ(s.enforce(0.2, 0.079, 0.01), 0.08);
}

TEST(PositionSaturation, NoLimitsPassesTheCommand) {
  PositionSaturation s(JointLimits{});
  EXPECT_DOUBLE_EQ(s.enforce(1e6, 0.0, 0.001), 1e6);
  EXPECT_DOUBLE_EQ(s.enforce(-1e6, 0.0, 0.001), -1e6);
}

TEST(VelocitySaturation, ClampsToMaxVelocityAndAcceleration) {
  JointLimits l = finger();
  VelocitySaturation s(l);
  EXPECT_DOUBLE_EQ(s.enforce(3.0, 0.001), 0.5);
  EXPECT_DOUBLE_EQ(s.enforce(-3.0, 0.001), -0.5);
  EXPECT_DOUBLE_EQ(s.enforce(0.2, 0.001), 0.2);
  l.has_acceleration_limits = true;
  l.max_acceleration = 10.0;
  VelocitySaturation a(l);
  EXPECT_DOUBLE_EQ(a.enforce(3.0, 0.01), 0.1);  // from 0, 10 m/s^2 * 0.01 s
  EXPECT_DOUBLE_EQ(a.enforce(3.0, 0.01), 0.2);
  EXPECT_DOUBLE_EQ(a.enforce(-3.0, 0.01), 0.1);
  EXPECT_DOUBLE_EQ(a.enforce(3.0, 1.0), 0.5);  // max_velocity still bounds it
}

TEST(EffortSaturation, ClampsAndPushesNoFurtherPastALimit) {
  const JointLimits l = finger();
  EXPECT_DOUBLE_EQ(enforceEffortSaturation(l, 50.0, 0.04, 0.0), 20.0);
  EXPECT_DOUBLE_EQ(enforceEffortSaturation(l, -50.0, 0.04, 0.0), -20.0);
  // past the upper position limit: no positive effort, negative allowed
  EXPECT_DOUBLE_EQ(enforceEffortSaturation(l, 5.0, 0.081, 0.0), 0.0);
  EXPECT_DOUBLE_EQ(enforceEffortSaturation(l, -5.0, 0.081, 0.0), -5.0);
  // below the lower one: no negative effort
  EXPECT_DOUBLE_EQ(enforceEffortSaturation(l, -5.0, -0.001, 0.0), 0.0);
  EXPECT_DOUBLE_EQ(enforceEffortSaturation(l, 5.0, -0.001, 0.0), 5.0);
  // faster than max_velocity: no effort that speeds it up further
  EXPECT_DOUBLE_EQ(enforceEffortSaturation(l, 5.0, 0.04, 0.6), 0.0);
  EXPECT_DOUBLE_EQ(enforceEffortSaturation(l, -5.0, 0.04, 0.6), -5.0);
  EXPECT_DOUBLE_EQ(enforceEffortSaturation(l, -5.0, 0.04, -0.6), 0.0);
}

// Soft limits (URDF <safety_controller>): the finger with soft limits 0.01 and 0.07 m,
// k_position 10, k_velocity 5 (joint_limits_interface.h's *SoftLimitsHandle).
namespace {
tianracer_control::SoftJointLimits fingerSoft() {
  tianracer_control::SoftJointLimits s;
  s.min_position = 0.01;
  s.max_position = 0.07;
  s.k_position = 10.0;
  s.k_velocity = 5.0;
  return s;
}
}  // namespace

TEST(PositionSoftLimits, SlowsTheCommandNearASoftLimitAndPushesItBackPastIt) {
  tianracer_control::PositionSoftLimits s(finger(), fingerSoft());
  // from the position 0.065: upward at most -10 * (0.065 - 0.07) = 0.05 m/s for 0.01 s
  EXPECT_NEAR(s.enforce(0.2, 0.065, 0.01), 0.0655, 1e-12);
  // then from the previous command: 0.045 m/s
  EXPECT_NEAR(s.enforce(0.2, 0.0, 0.01), 0.06595, 1e-12);
  s.reset();
  // past the soft limit (0.075): the bound is -0.05 m/s, the command moves back in
  EXPECT_NEAR(s.enforce(0.08, 0.075, 0.01), 0.0745, 1e-12);
  // downward from 0.04: at most -10 * (0.04 - 0.01) = -0.3 m/s
  s.reset();
  EXPECT_NEAR(s.enforce(-1.0, 0.04, 0.01), 0.037, 1e-12);
  // from 0.065 downward: -0.55 m/s is beyond max_velocity, so 0.5 m/s
  s.reset();
  EXPECT_NEAR(s.enforce(-1.0, 0.065, 0.01), 0.06, 1e-12);
}

TEST(EffortSoftLimits, BoundsTheEffortByTheSoftVelocityBounds) {
  using tianracer_control::enforceEffortSoftLimits;
  // at 0.075 m at rest: velocity bounds [-0.5, -0.05] -> effort bounds [-2.5, -0.25]
  EXPECT_NEAR(enforceEffortSoftLimits(finger(), fingerSoft(), 10.0, 0.075, 0.0), -0.25, 1e-12);
  EXPECT_NEAR(enforceEffortSoftLimits(finger(), fingerSoft(), -10.0, 0.075, 0.0), -2.5, 1e-12);
  // in the middle (0.04) at rest: [-0.3, 0.3] m/s -> [-1.5, 1.5] N; within max_effort 20
  EXPECT_NEAR(enforceEffortSoftLimits(finger(), fingerSoft(), 30.0, 0.04, 0.0), 1.5, 1e-12);
  EXPECT_NEAR(enforceEffortSoftLimits(finger(), fingerSoft(), 1.0, 0.04, 0.0), 1.0, 1e-12);
}

TEST(VelocitySoftLimits, BoundsTheVelocityByPositionAndAcceleration) {
  using tianracer_control::enforceVelocitySoftLimits;
  // at 0.075: at most -0.05 m/s
  EXPECT_NEAR(enforceVelocitySoftLimits(finger(), fingerSoft(), 0.3, 0.075, 0.1, 0.01), -0.05,
              1e-12);
  // in the middle with an acceleration limit of 2 m/s^2: within 0.02 m/s of the velocity 0.1
  JointLimits l = finger();
  l.has_acceleration_limits = true;
  l.max_acceleration = 2.0;
  EXPECT_NEAR(enforceVelocitySoftLimits(l, fingerSoft(), 0.3, 0.04, 0.1, 0.01), 0.12, 1e-12);
  // no velocity and no position limits: unbounded
  JointLimits none;
  EXPECT_DOUBLE_EQ(enforceVelocitySoftLimits(none, fingerSoft(), 1e6, 0.5, 0.0, 0.01), 1e6);
}
