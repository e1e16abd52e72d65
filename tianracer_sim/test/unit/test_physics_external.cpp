// Link twists and external wrenches (what the Gazebo interface's link_states and
// apply_body_wrench read and write).
#include <cmath>

#include <gtest/gtest.h>

#include "physics_test_support.h"

namespace tianracer_sim {
namespace {

// The arm hinged 0.2 m ahead of the base's origin, +-3 rad, with a sensor link fixed at its end
// (merged into its body): the COM of the arm is off its frame.
const std::string kArm = armRobot("0.2 0 0", "3", R"(  <link name="tip"/>
  <joint name="tip_joint" type="fixed">
    <parent link="arm"/><child link="tip"/><origin xyz="1 0.1 0"/>
  </joint>
)");

const char* kBox = R"(<robot name="box"><link name="base_link">
    <inertial><origin xyz="0 0 0.1"/><mass value="2"/>
      <inertia ixx="0.02" ixy="0" ixz="0" iyy="0.03" iyz="0" izz="0.04"/></inertial>
  </link></robot>)";

TEST(PhysicsExternal, LinkTwistIsTheDerivativeOfTheLinkPose) {
  const PhysicsOptions o = weightless();
  PhysicsWorld w(o);
  PhysicsRobot& r = w.robot(addTestRobot(w, parseTestRobot(kArm), at(1, 2, 3, 0.5), "arm"));
  Twist base;
  base.linear = {0.3, -0.2, 0.1};
  base.angular = {0.2, -0.1, 0.8};
  r.setBaseTwist(base);
  r.setJointState(r.jointIndex("hinge"), 0.4, 1.5);
  for (int k = 0; k < 5; ++k) w.step();
  // The base's own twist is baseTwist().
  const Twist b = r.linkTwist("base_link");
  EXPECT_TRUE(b.linear.isApprox(r.baseTwist().linear, 1e-12));
  EXPECT_TRUE(b.angular.isApprox(r.baseTwist().angular, 1e-12));
  // Central differences of the poses over +-1 step against the twist in the middle: they
  // differ by the semi-implicit integrator's a dt / 2 (~1e-4 here); a twist in the wrong
  // frame or about the wrong point would be off by ~1.
  for (const char* link : {"arm", "tip"}) {
    const Eigen::Isometry3d X0 = r.linkPose(link);
    w.step();
    const Twist v1 = r.linkTwist(link);
    w.step();
    const Eigen::Isometry3d X2 = r.linkPose(link);
    const double dt = o.dt;
    const Eigen::Vector3d v_fd = (X2.translation() - X0.translation()) / (2 * dt);
    const Eigen::AngleAxisd dR(X2.linear() * X0.linear().transpose());
    const Eigen::Vector3d w_fd = dR.axis() * dR.angle() / (2 * dt);
    EXPECT_LT((v1.linear - v_fd).norm(), 1e-3) << link << ": " << v1.linear.transpose()
                                               << " vs " << v_fd.transpose();
    EXPECT_LT((v1.angular - w_fd).norm(), 1e-3) << link << ": " << v1.angular.transpose()
                                                << " vs " << w_fd.transpose();
    EXPECT_GT((v1.linear - b.linear).norm(), 0.1);  // not the base's velocity
  }
  EXPECT_THROW(r.linkTwist("nope"), PhysicsError);
}

TEST(PhysicsExternal, WrenchThroughTheCentreOfMass) {
  const PhysicsOptions o = weightless();
  PhysicsWorld w(o);
  PhysicsRobot& r = w.robot(addTestRobot(w, parseTestRobot(kBox), at(0, 0, 0, 0.7), "box"));
  r.setExternalWrench("base_link", {2.0, 0.0, 0.0}, {0.0, 0.0, 0.04});
  const int n = 1000;
  for (int k = 0; k < n; ++k) w.step();
  // a = F/m = 1 m/s^2, alpha = tau/I = 1 rad/s^2 for 1 s; no spin-induced drift of the COM.
  const Eigen::Vector3d com = r.basePose() * Eigen::Vector3d(0, 0, 0.1);
  const double dt = o.dt;
  EXPECT_NEAR(com.x(), dt * dt * n * (n + 1) / 2.0, 1e-9);  // semi-implicit Euler
  EXPECT_NEAR(com.y(), 0.0, 1e-9);
  EXPECT_NEAR(r.baseTwist().angular.z(), 1.0, 1e-9);
  // Replaced by zero: the velocities hold.
  r.setExternalWrench("base_link", Eigen::Vector3d::Zero(), Eigen::Vector3d::Zero());
  const double wz = r.baseTwist().angular.z();
  for (int k = 0; k < 100; ++k) w.step();
  EXPECT_NEAR(r.baseTwist().angular.z(), wz, 1e-9);
  // Non-finite: rejected and counted; resetToSpawn clears a wrench.
  const auto rejected = r.rejectedCommands();
  r.setExternalWrench("base_link", {NAN, 0, 0}, Eigen::Vector3d::Zero());
  EXPECT_EQ(r.rejectedCommands(), rejected + 1);
  r.setExternalWrench("base_link", {5, 0, 0}, Eigen::Vector3d::Zero());
  r.resetToSpawn();
  for (int k = 0; k < 10; ++k) w.step();
  EXPECT_EQ(r.baseTwist().linear.norm(), 0.0);
  EXPECT_THROW(r.setExternalWrench("nope", Eigen::Vector3d::Zero(), Eigen::Vector3d::Zero()),
               PhysicsError);
}

}  // namespace
}  // namespace tianracer_sim
