// Penetration recovery (world.h): a robot spawned overlapping a static shape or another robot is
// pushed out at no more than its contacts' max_vel (ODE's rule), not thrown away by Bullet's
// unlimited position correction (erp2 x depth / dt: 6 m/s for 3 cm at 1 ms).
#include <gtest/gtest.h>

#include <cmath>
#include <iostream>

#include <urdf_parser/urdf_parser.h>

#include "physics_test_support.h"
#include "tianracer_sim/physics/world.h"

namespace tianracer_sim {
namespace {

TestRobot cube(double side = 0.1) {
  const double m = 2.0, I = m * side * side / 6.0;
  TestRobot model;
  model.urdf = urdf::parseURDF(
      "<robot name='cube'><link name='base_link'><inertial><mass value='" + std::to_string(m) +
      "'/><inertia ixx='" + std::to_string(I) + "' ixy='0' ixz='0' iyy='" + std::to_string(I) +
      "' iyz='0' izz='" + std::to_string(I) + "'/></inertial><collision><geometry><box size='" +
      std::to_string(side) + " " + std::to_string(side) + " " + std::to_string(side) +
      "'/></geometry></collision></link></robot>");
  if (!model.urdf) throw std::runtime_error("bad test URDF");
  return model;
}

/// A 1 m static box at the origin.
StaticShape block() {
  StaticShape s;
  s.name = "block";
  s.shape.type = ShapeType::kBox;
  s.shape.size = Eigen::Vector3d::Ones();
  return s;
}

bool finite(const PhysicsRobot& r) {
  return r.basePose().matrix().allFinite() && r.baseTwist().linear.allFinite() &&
         r.baseTwist().angular.allFinite();
}

/// Steps `seconds` and returns the highest base speed seen; fails on a non-finite state.
double run(PhysicsWorld& w, const PhysicsRobot& r, double seconds) {
  double top = 0.0;
  for (long k = 0, n = std::lround(seconds / w.dt()); k < n; ++k) {
    w.step();
    EXPECT_TRUE(finite(r)) << "step " << k;
    if (!finite(r)) break;
    top = std::max(top, r.baseTwist().linear.norm());
  }
  return top;
}

// A 10 cm cube 3 cm deep in a static box, weightless: it leaves along the face normal at exactly
// the cap (nothing slows it down afterwards), Bullet alone would give 0.2 x 0.03 / 0.001 = 6 m/s.
TEST(PenetrationRecovery, CubeInAStaticBoxLeavesAtTheCap) {
  PhysicsWorld w(weightless());
  w.addStaticShape(block());
  PhysicsRobot& r = w.robot(addTestRobot(w, cube(), at(0.5 + 0.05 - 0.03, 0, 0), "cube"));
  const double top = run(w, r, 1.0);
  const Twist t = r.baseTwist();
  std::cout << "[cube 3 cm in a box] exit velocity " << t.linear.transpose() << " m/s (cap "
            << w.options().contact_max_vel << "), highest " << top << ", x after 1 s "
            << r.basePose().translation().x() << "\n";
  EXPECT_NEAR(t.linear.x(), w.options().contact_max_vel, 1e-6);
  EXPECT_LT(t.linear.tail<2>().norm(), 1e-6);  // straight out along the face normal
  EXPECT_LT(t.angular.norm(), 1e-5);
  EXPECT_LE(top, w.options().contact_max_vel + 1e-6);
  EXPECT_GT(r.basePose().translation().x(), 0.55 + 0.05);  // out, and moving on
}

// The link's <maxVel> and the world's contact_max_correcting_vel, as in Gazebo: the smaller wins.
TEST(PenetrationRecovery, MaxVelTagAndWorldCap) {
  struct Case {
    double tag, world, expected;
  };
  for (const Case& c : {Case{0.5, 100.0, 0.5}, Case{0.5, 0.2, 0.2}, Case{-1.0, 0.3, 0.3}}) {
    PhysicsOptions o = weightless();
    o.contact_max_correcting_vel = c.world;
    PhysicsWorld w(o);
    w.addStaticShape(block());
    TestRobot m = cube();
    m.surfaces["base_link"].max_vel = c.tag;  // < 0: the world's cap (Gazebo)
    PhysicsRobot& r = w.robot(addTestRobot(w, m, at(0.5 + 0.05 - 0.03, 0, 0), "cube"));
    run(w, r, 0.5);
    EXPECT_NEAR(r.baseTwist().linear.x(), c.expected, 1e-6) << c.tag << " " << c.world;
  }
}

// <minDepth> is penetration left alone: a cube spawned 3 mm into the ground comes up until it is
// that deep (without it: until it touches). Contacts still stop any approach: resting contact
// itself does not sink into min_depth.
TEST(PenetrationRecovery, MinDepthIsPenetrationLeftAlone) {
  for (const double min_depth : {0.0, 0.001}) {
    PhysicsWorld w;
    TestRobot m = cube();
    m.surfaces["base_link"].min_depth = min_depth;
    PhysicsRobot& r = w.robot(addTestRobot(w, m, at(0, 0, 0.05 - 0.003), "cube"));
    const double top = run(w, r, 2.0);
    const double depth = 0.05 - r.basePose().translation().z();
    std::cout << "[cube 3 mm into the ground, minDepth " << min_depth * 1e3 << " mm] depth after 2 s "
              << depth * 1e3 << " mm, highest speed " << top << " m/s\n";
    EXPECT_NEAR(depth, min_depth, 2e-4) << min_depth;
    EXPECT_LE(top, w.options().contact_max_vel + 1e-6);
    EXPECT_LT(r.baseTwist().linear.norm(), 1e-4);
  }
}

// Two robots spawned 4 cm into each other: they part at the cap (relative normal velocity).
TEST(PenetrationRecovery, OverlappingRobotsPartAtTheCap) {
  PhysicsWorld w(weightless());
  PhysicsRobot& a = w.robot(addTestRobot(w, cube(), at(0, 0, 0), "a"));
  PhysicsRobot& b = w.robot(addTestRobot(w, cube(), at(0.06, 0, 0), "b"));
  double top = 0.0;
  for (int k = 0; k < 1000; ++k) {
    w.step();
    ASSERT_TRUE(finite(a) && finite(b)) << "step " << k;
    top = std::max(top, (b.baseTwist().linear - a.baseTwist().linear).norm());
  }
  const double parting = b.baseTwist().linear.x() - a.baseTwist().linear.x();
  std::cout << "[two cubes 4 cm into each other] parting speed " << parting << " m/s, highest "
            << top << "\n";
  EXPECT_NEAR(parting, w.options().contact_max_vel, 1e-6);
  EXPECT_NEAR(a.baseTwist().linear.x(), -b.baseTwist().linear.x(), 1e-9);  // equal masses
  EXPECT_LE(top, w.options().contact_max_vel + 1e-6);
}

// Deep (a cube half inside a box, under gravity, on the ground): still bounded and finite.
TEST(PenetrationRecovery, HalfBuriedCubeStaysBoundedOnTheGround) {
  PhysicsWorld w;
  StaticShape s = block();
  s.X_WS = at(0, 0, 0.5);
  w.addStaticShape(s);
  PhysicsRobot& r = w.robot(addTestRobot(w, cube(), at(0.5, 0, 0.05), "cube"));
  const double top = run(w, r, 3.0);
  const Eigen::Vector3d p = r.basePose().translation();
  std::cout << "[cube half in a box on the ground] highest speed " << top << " m/s, after 3 s at "
            << p.transpose() << "\n";
  EXPECT_LT(top, 2.0 * w.options().contact_max_vel);
  EXPECT_GT(p.x(), 0.5 + 0.05 - 1e-3);  // pushed out (or resting against the face)
  EXPECT_LT(r.baseTwist().linear.norm(), 1e-3);
}

}  // namespace
}  // namespace tianracer_sim
