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
