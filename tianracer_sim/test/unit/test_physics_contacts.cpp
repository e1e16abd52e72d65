// Robots' contacts (contacts.h): what touches what, when, where and how hard.
#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "physics_test_support.h"
#include "tianracer_sim/physics/contacts.h"
#include "tianracer_sim/physics/world.h"

namespace tianracer_sim {
namespace {

TestRobot cube() {
  // 10 cm, 2 kg
  return parseTestRobot(
      "<robot name='cube'><link name='base_link'><inertial><mass value='2'/><inertia ixx='0.0033' "
      "ixy='0' ixz='0' iyy='0.0033' iyz='0' izz='0.0033'/></inertial><collision><geometry><box "
      "size='0.1 0.1 0.1'/></geometry></collision></link></robot>");
}

// A weightless cube sliding at 1 m/s into a 1 m static box: contact begins when its face
// reaches the box's (0.45 s), against static shape 0, with the normal pushing it back.
TEST(RobotContacts, SlidingIntoAStaticBox) {
  PhysicsWorld w(weightless());
  StaticShape box;
  box.name = "wall::link::collision";
  box.shape.size = Eigen::Vector3d::Ones();
  w.addStaticShape(box);
  const RobotId id = addTestRobot(w, cube(), at(-1.0, 0.0, 0.0), "cube");
  Twist v;
  v.linear = Eigen::Vector3d(1.0, 0.0, 0.0);
  w.robot(id).setBaseTwist(v);
  std::vector<RobotContact> contacts;
  double t_first = -1.0;
  for (int k = 0; k < 1000 && t_first < 0.0; ++k) {
    w.step();
    robotContacts(w, id, &contacts);
    if (!contacts.empty()) t_first = w.time();
  }
  // Face to face 0.45 m apart at 1 m/s; Bullet reports points up to 1 mm before they touch.
  EXPECT_NEAR(t_first, 0.45, 0.003);
  ASSERT_EQ(contacts.size(), 1u);
  const RobotContact& c = contacts[0];
  EXPECT_EQ(c.body, 0);
  EXPECT_EQ(c.other_static, 0);
  EXPECT_EQ(c.other_robot, -1);
  EXPECT_FALSE(c.ground);
  EXPECT_NEAR(c.normal_W.x(), -1.0, 1e-6);
  EXPECT_NEAR(c.position_W.x(), -0.5, 0.002);
  EXPECT_GE(c.depth, 0.0);
  // The cube is stopped: the impulses from the first contact on take its momentum (2 kg x 1 m/s).
  double impulse = c.impulse;
  for (int k = 0; k < 50; ++k) {
    w.step();
    robotContacts(w, id, &contacts);
    for (const RobotContact& x : contacts) impulse += x.impulse;
  }
  EXPECT_NEAR(impulse, 2.0, 0.2);
  EXPECT_LT(std::abs(w.robot(id).baseTwist().linear.x()), 0.2);
}

// Standing on the ground is a contact with the ground (only wheels on the ground are left out);
// two robots side by side see each other by id and body.
TEST(RobotContacts, GroundAndAnotherRobot) {
  PhysicsWorld w;
  const RobotId a = addTestRobot(w, cube(), at(0.0, 0.0, 0.0499), "a");
  const RobotId b = addTestRobot(w, cube(), at(0.0999, 0.0, 0.0499), "b");
  w.step();  // 0.1 mm overlaps: touching in the first step, before recovery parts them
  std::vector<RobotContact> contacts;
  robotContacts(w, a, &contacts);
  bool ground = false, other = false;
  for (const RobotContact& c : contacts) {
    if (c.ground) {
      ground = true;
      EXPECT_NEAR(c.normal_W.z(), 1.0, 1e-3);
    }
    if (c.other_robot == b) {
      other = true;
      EXPECT_EQ(c.other_body, 0);
      EXPECT_LT(c.normal_W.x(), -0.9);  // pushes a (on the left) away from b
    }
  }
  EXPECT_TRUE(ground);
  EXPECT_TRUE(other);
}

}  // namespace
}  // namespace tianracer_sim
