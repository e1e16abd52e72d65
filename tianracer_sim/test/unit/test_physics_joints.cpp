// Joint damping applied implicitly (JointDamper), and the memory of a long chain (issue 43).
#include <gtest/gtest.h>

#include <malloc.h>

#include <chrono>
#include <cmath>
#include <string>

#include "physics_test_support.h"

namespace tianracer_sim {
namespace {

/// A wheel of inertia `izz` about its axle z on a base welded to the world, the axle damped
/// by `damping`: the joint's effective inertia is izz exactly.
std::string dampedWheel(double izz, double damping) {
  return R"(<robot name="wheel">
  <link name="world"/>
  <link name="base"><inertial><mass value="1"/>
    <inertia ixx="0.01" ixy="0" ixz="0" iyy="0.01" iyz="0" izz="0.01"/></inertial></link>
  <joint name="weld" type="fixed"><parent link="world"/><child link="base"/></joint>
  <link name="wheel"><inertial><mass value="0.2"/>
    <inertia ixx=")" + std::to_string(izz) + R"(" ixy="0" ixz="0" iyy=")" + std::to_string(izz) +
         R"(" iyz="0" izz=")" + std::to_string(izz) + R"("/></inertial></link>
  <joint name="axle" type="continuous"><parent link="base"/><child link="wheel"/>
    <axis xyz="0 0 1"/><dynamics damping=")" + std::to_string(damping) + R"("/></joint>
</robot>)";
}

struct Spin {
  std::vector<double> v;  // joint velocity after each step
};

Spin spinDown(double izz, double damping, double v0, int steps) {
  PhysicsWorld w(weightless());
  const TestRobot m = parseTestRobot(dampedWheel(izz, damping));
  PhysicsRobot& r = w.robot(addTestRobot(w, m, Eigen::Isometry3d::Identity(), "wheel"));
  r.setJointState(0, 0.0, v0);
  Spin s;
  for (int k = 0; k < steps; ++k) {
    w.step();
    s.v.push_back(r.jointVelocity(0));
  }
  return s;
}

TEST(JointDamping, StiffDampingOnALightWheelDecaysWithoutOvershoot) {
  // Damping 3 on 1e-3 kg m^2 at h = 1 ms: h c / I = 3. Explicitly, v' = v (1 - 3) = -2 v: it
  // doubled and flipped every step (the robot thrown 46 m in 0.2 s). Implicitly,
  // v' = v / (1 + 3) each step: it only decays, and never changes sign.
  const double h = PhysicsOptions().dt, c = 3.0, I = 1e-3, v0 = 10.0;
  const Spin s = spinDown(I, c, v0, 50);
  double prev = v0;
  for (std::size_t k = 0; k < s.v.size(); ++k) {
    ASSERT_TRUE(std::isfinite(s.v[k]));
    EXPECT_GE(s.v[k], 0.0) << "step " << k;
    EXPECT_LE(s.v[k], prev) << "step " << k;
    prev = s.v[k];
  }
  const double expected1 = v0 / (1.0 + h * c / I);
  EXPECT_NEAR(s.v[0], expected1, 1e-3 * expected1);
  EXPECT_LT(s.v.back(), 1e-12);
}

TEST(JointDamping, LightDampingDecaysAsTheContinuousLaw) {
  // h c / I = 0.01: after 0.2 s, v = v0 exp(-c t / I) within 1 % (implicit Euler's error is
  // O(h c / I) per time constant).
  const double c = 1e-5, I = 1e-3, v0 = 10.0;
  const int steps = 200;
  const Spin s = spinDown(I, c, v0, steps);
  const double t = steps * PhysicsOptions().dt;
  const double exact = v0 * std::exp(-c * t / I);
  EXPECT_NEAR(s.v.back(), exact, 0.01 * exact);
  // And without damping nothing decays.
  EXPECT_NEAR(spinDown(I, 0.0, v0, steps).v.back(), v0, 1e-9);
}

TEST(JointDamping, HugeDampingHoldsTheJointAndStaysFinite) {
  const Spin s = spinDown(1e-3, 1e6, 10.0, 20);
  for (double v : s.v) {
    ASSERT_TRUE(std::isfinite(v));
    EXPECT_LT(std::abs(v), 1e-3);
  }
}

/// A chain of `n` links on revolute joints with limits, hanging from a base.
std::string chain(int n) {
  std::string x = "<robot name='chain'><link name='l0'><inertial><mass value='1'/>"
                  "<inertia ixx='0.01' ixy='0' ixz='0' iyy='0.01' iyz='0' izz='0.01'/></inertial></link>";
  for (int i = 1; i < n; ++i) {
    const std::string l = "l" + std::to_string(i), p = "l" + std::to_string(i - 1);
    x += "<link name='" + l + "'><inertial><mass value='0.1'/>"
         "<inertia ixx='0.001' ixy='0' ixz='0' iyy='0.001' iyz='0' izz='0.001'/></inertial></link>"
         "<joint name='j" + std::to_string(i) + "' type='revolute'><parent link='" + p +
         "'/><child link='" + l + "'/><origin xyz='0.1 0 0'/><axis xyz='0 0 1'/>"
         "<limit lower='-1' upper='1' effort='1' velocity='1'/></joint>";
  }
  return x + "</robot>";
}

TEST(JointMemory, AChainOfAThousandLinksDoesNotAllocateConstraintsPerJoint) {
  // Bullet's limit and motor constraints hold rows over every DOF of the multibody: made for
  // each of n joints up front, (2 limit + 1 motor rows) x 2 (6 + n) doubles each, 48 MB for
  // n = 1000 and 19 GB for 20,000. They are made when first used now.
  const TestRobot m = parseTestRobot(chain(1000));
  const std::size_t before = mallinfo2().uordblks;
  const auto t0 = std::chrono::steady_clock::now();
  PhysicsWorld w(weightless());
  PhysicsRobot& r = w.robot(addTestRobot(w, m, Eigen::Isometry3d::Identity(), "chain"));
  for (int k = 0; k < 10; ++k) w.step();
  const std::size_t after = mallinfo2().uordblks;
  const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  EXPECT_LT(after - before, 16u << 20) << "bytes: " << (after - before);
  EXPECT_LT(seconds, 20.0);
  ASSERT_EQ(r.joints().size(), 999u);
  // A joint that reaches its limit still stops there (its limit made on the way).
  r.setJointState(5, 0.9, 5.0);
  for (int k = 0; k < 100; ++k) w.step();
  EXPECT_LT(r.jointPosition(5), 1.0 + 0.02);
}

}  // namespace
}  // namespace tianracer_sim
