// Entity names, states relative to other entities (gazebo_ros's get/set semantics), and the
// wrench schedule of apply_body_wrench.
#include <cmath>
#include <limits>

#include <gtest/gtest.h>

#include "tianracer_sim/simulator/entity_state.h"

namespace tianracer_sim {
namespace {

Eigen::Isometry3d pose(double x, double y, double z, double yaw) {
  Eigen::Isometry3d X = Eigen::Isometry3d::Identity();
  X.linear() = Eigen::AngleAxisd(yaw, Eigen::Vector3d::UnitZ()).toRotationMatrix();
  X.translation() = Eigen::Vector3d(x, y, z);
  return X;
}

EntityState state(const Eigen::Isometry3d& X, const Eigen::Vector3d& v, const Eigen::Vector3d& w) {
  EntityState s;
  s.X_WE = X;
  s.V_WE.linear = v;
  s.V_WE.angular = w;
  return s;
}

TEST(EntityNames, ScopedNames) {
  EXPECT_EQ(splitScopedName("tianracer::base_link").model, "tianracer");
  EXPECT_EQ(splitScopedName("tianracer::base_link").link, "base_link");
  EXPECT_EQ(splitScopedName("box").model, "box");
  EXPECT_EQ(splitScopedName("box").link, "");
  EXPECT_EQ(splitScopedName("a::b::c").link, "b::c");
  EXPECT_TRUE(isWorldFrame(""));
  EXPECT_TRUE(isWorldFrame("world"));
  EXPECT_TRUE(isWorldFrame("map"));
  EXPECT_FALSE(isWorldFrame("tianracer"));
}

TEST(EntityState, RelativePoseAndTwistByHand) {
  // Frame F at (1, 0, 0) turned 90 deg, moving at (0.5, 0, 0) and turning at 1 rad/s.
  const EntityState F = state(pose(1, 0, 0, M_PI / 2), {0.5, 0, 0}, {0, 0, 1});
  // Entity at (1, 2, 0), yaw 90 deg + 0.3, moving at (0.5, 1, 0), turning at 1.5 rad/s.
  const EntityState E = state(pose(1, 2, 0, M_PI / 2 + 0.3), {0.5, 1, 0}, {0, 0, 1.5});
  const EntityState r = relativeTo(E, F);
  EXPECT_NEAR(r.X_WE.translation().x(), 2.0, 1e-12);  // 2 m ahead along F's x (world y)
  EXPECT_NEAR(r.X_WE.translation().y(), 0.0, 1e-12);
  EXPECT_NEAR(Eigen::AngleAxisd(r.X_WE.linear()).angle(), 0.3, 1e-12);
  // (0, 1, 0) in the world is +x in F; no w_F x r term (gazebo_ros subtracts velocities only).
  EXPECT_NEAR(r.V_WE.linear.x(), 1.0, 1e-12);
  EXPECT_NEAR(r.V_WE.linear.y(), 0.0, 1e-12);
  EXPECT_NEAR(r.V_WE.angular.z(), 0.5, 1e-12);
}

TEST(EntityState, FromFrameInvertsThePoseAndRotatesTheTwist) {
  const EntityState F = state(pose(-2, 1, 0.5, 0.7), {3, 0, 0}, {0, 0, 2});
  const EntityState in_F = state(pose(0.4, -0.1, 0.2, -0.2), {1, 0, 0}, {0, 0, 0.1});
  const EntityState W = fromFrame(in_F, F);
  const EntityState back = relativeTo(W, state(F.X_WE, {0, 0, 0}, {0, 0, 0}));
  EXPECT_TRUE(back.X_WE.isApprox(in_F.X_WE, 1e-12));
  EXPECT_TRUE(back.V_WE.linear.isApprox(in_F.V_WE.linear, 1e-12));
  EXPECT_NEAR(W.V_WE.linear.x(), std::cos(0.7), 1e-12);  // rotated only, F's speed not added
  EXPECT_NEAR(W.V_WE.linear.y(), std::sin(0.7), 1e-12);
  EXPECT_NEAR(W.V_WE.angular.z(), 0.1, 1e-12);
}

TEST(EntityState, WorldFrameIsIdentity) {
  const EntityState E = state(pose(1, 2, 3, 0.4), {1, 2, 3}, {0.1, 0.2, 0.3});
  const EntityState r = relativeTo(E, EntityState());
  EXPECT_TRUE(r.X_WE.isApprox(E.X_WE, 1e-15));
  EXPECT_TRUE(r.V_WE.linear.isApprox(E.V_WE.linear, 1e-15));
}

TEST(EntityState, ShiftTwistAlongARigidBody) {
  Twist V;
  V.linear = {1, 0, 0};
  V.angular = {0, 0, 2};
  const Twist s = shiftTwist(V, {0, 0, 0}, {0, 0.5, 0});
  EXPECT_NEAR(s.linear.x(), 1.0 - 2.0 * 0.5, 1e-12);  // w x r = (0,0,2) x (0,0.5,0) = (-1,0,0)
  EXPECT_NEAR(s.linear.y(), 0.0, 1e-12);
  EXPECT_NEAR(s.angular.z(), 2.0, 1e-12);
}

TEST(WrenchSchedule, StartDurationAndSums) {
  WrenchSchedule s;
  const double dt = 0.001;
  ScheduledWrench a;
  a.body = "box::link";
  a.force_W = {1, 0, 0};
  a.start = 0.0;                      // in the past: now
  ASSERT_TRUE(s.add(a, 1.0, 0.5, dt));  // [1.0, 1.5)
  ScheduledWrench b = a;
  b.force_W = {0, 2, 0};
  b.start = 1.2;
  ASSERT_TRUE(s.add(b, 1.0, -1.0, dt));  // [1.2, inf)
  EXPECT_FALSE(s.add(b, 1.0, 0.0, dt));  // duration 0: nothing
  EXPECT_TRUE(s.totals(0.999).empty());
  ASSERT_EQ(s.totals(1.0).size(), 1u);
  EXPECT_EQ(s.totals(1.1)[0].force_W, Eigen::Vector3d(1, 0, 0));
  EXPECT_EQ(s.totals(1.2)[0].force_W, Eigen::Vector3d(1, 2, 0));
  EXPECT_EQ(s.totals(1.499)[0].force_W, Eigen::Vector3d(1, 2, 0));
  EXPECT_EQ(s.totals(1.5)[0].force_W, Eigen::Vector3d(0, 2, 0));
  EXPECT_EQ(s.clear("box::link"), 1);
  // Cleared: reported once with zero so that the force is switched off, then nothing.
  ASSERT_EQ(s.totals(1.6).size(), 1u);
  EXPECT_TRUE(s.totals(1.6).empty());
  EXPECT_TRUE(s.empty());
}

TEST(WrenchSchedule, ShorterThanAStepActsForOneStep) {
  WrenchSchedule s;
  ScheduledWrench a;
  a.body = "m::l";
  a.force_W = {0, 0, 5};
  ASSERT_TRUE(s.add(a, 2.0, 1e-6, 0.001));
  EXPECT_EQ(s.totals(2.0).size(), 1u);
  EXPECT_EQ(s.totals(2.0)[0].force_W.z(), 5.0);
  ASSERT_EQ(s.totals(2.001).size(), 1u);  // the switch-off
  EXPECT_EQ(s.totals(2.001)[0].force_W.z(), 0.0);
}

TEST(WrenchSchedule, ClearAll) {
  WrenchSchedule s;
  ScheduledWrench a;
  a.body = "x::y";
  a.torque_W = {0, 0, 1};
  s.add(a, 0.0, -1.0, 0.001);
  a.body = "z::w";
  s.add(a, 0.0, -1.0, 0.001);
  EXPECT_EQ(s.totals(0.0).size(), 2u);
  EXPECT_EQ(s.clear(), 2);
  EXPECT_EQ(s.totals(0.001).size(), 2u);  // both switched off
  EXPECT_TRUE(s.totals(0.002).empty());
}

}  // namespace
}  // namespace tianracer_sim
