// checkModelState: the bounds on a base state set from outside (spawn, set_model_state). Issue 9:
// a set_model_state at x = 1e30 was accepted and the lidar's ray caster then aborted the node.
#include <cmath>
#include <limits>

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "tianracer_sim/sim/simulation.h"

namespace tianracer_sim {
namespace {

using ::testing::HasSubstr;

Eigen::Isometry3d at(double x, double y, double z) {
  Eigen::Isometry3d X = Eigen::Isometry3d::Identity();
  X.translation() = Eigen::Vector3d(x, y, z);
  return X;
}

TEST(CheckModelState, WithinBoundsIsFine) {
  EXPECT_EQ(checkModelState(at(0, 0, 0), Twist()), "");
  Twist v;
  v.linear = Eigen::Vector3d(kMaxModelLinearVelocity, 0, -kMaxModelLinearVelocity);
  v.angular = Eigen::Vector3d(0, kMaxModelAngularVelocity, 0);
  EXPECT_EQ(checkModelState(at(kMaxModelPosition, -kMaxModelPosition, 0), v), "");
}

TEST(CheckModelState, HugeValuesNameTheComponentAndTheBound) {
  EXPECT_EQ(checkModelState(at(1e30, 0, 0), Twist()),
            "position x 1e+30 is out of range (|x| <= 1e+06 m)");
  EXPECT_THAT(checkModelState(at(0, 0, -1e30), Twist()), HasSubstr("position z -1e+30"));
  Twist v;
  v.linear.y() = 1e30;
  EXPECT_EQ(checkModelState(at(0, 0, 0), v),
            "linear velocity y 1e+30 is out of range (|y| <= 1000 m/s)");
  v = Twist();
  v.angular.z() = -1e30;
  EXPECT_EQ(checkModelState(at(0, 0, 0), v),
            "angular velocity z -1e+30 is out of range (|z| <= 10000 rad/s)");
}

TEST(CheckModelState, NonFinite) {
  const double nan = std::numeric_limits<double>::quiet_NaN();
  EXPECT_EQ(checkModelState(at(nan, 0, 0), Twist()), "pose is not finite");
  Twist v;
  v.angular.x() = std::numeric_limits<double>::infinity();
  EXPECT_EQ(checkModelState(at(0, 0, 0), v), "twist is not finite");
}

}  // namespace
}  // namespace tianracer_sim
