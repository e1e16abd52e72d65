// A link's <gravity>false</gravity> (SDF) or <gazebo reference> <turnGravityOff> (URDF): the link
// feels no gravity, as Gazebo's Link::SetGravityMode makes it (ODE: dBodySetGravityMode). Gazebo's
// own depth_camera2.world floats its box this way. Sim time only.
#include <gtest/gtest.h>

#include <cmath>
#include <string>

#include "sim_test_support.h"
#include "tianracer_sim/model/robot_model.h"
#include "tianracer_sim/sim/robot_physics.h"
#include "tianracer_sim/sim/world_physics.h"
#include "tianracer_sim/world/world.h"

namespace tianracer_sim {
namespace {

std::string box(const std::string& name, double y, const std::string& link_extra) {
  return "<model name='" + name + "'><pose>0 " + std::to_string(y) + " 1 0 0 0</pose><link name='l'>" + link_extra +
         "<inertial><mass>2</mass><inertia><ixx>0.1</ixx><iyy>0.1</iyy><izz>0.1</izz></inertia></inertial>"
         "<collision name='c'><geometry><box><size>0.2 0.2 0.2</size></box></geometry></collision></link></model>";
}

double stepFor(PhysicsWorld* world, double seconds) {
  const long n = std::lround(seconds / world->dt());
  for (long k = 0; k < n; ++k) world->step();
  return n * world->dt();
}

TEST(LinkGravity, AWorldModelLinkWithoutGravityFloats) {
  const WorldDescription desc = test::groundWorld(box("floating", 0.0, "<gravity>false</gravity>") +
                                                  box("falling", 2.0, "<gravity>true</gravity>"));
  PhysicsWorld world(physicsOptionsFor(desc));
  addWorldToPhysics(desc, &world, {});
  const PhysicsRobot& floating = world.freeBody(world.freeBodyIndex("floating"));
  const PhysicsRobot& falling = world.freeBody(world.freeBodyIndex("falling"));
  stepFor(&world, 0.2);
  EXPECT_NEAR(floating.linkPose("l").translation().z(), 1.0, 1e-9);
  EXPECT_NEAR(falling.linkPose("l").translation().z(), 1.0 - 0.5 * 9.8 * 0.2 * 0.2, 2e-3);
  stepFor(&world, 3.0);
  EXPECT_NEAR(floating.linkPose("l").translation().z(), 1.0, 1e-9);
  EXPECT_NEAR(falling.linkPose("l").translation().z(), 0.1, 1e-3);  // on the ground
}

// Two equal links welded into one body, only one of them feeling gravity: the body falls at g/2
// and turns about its COM (the force acts at the heavy side), as two ODE links would.
TEST(LinkGravity, HalfABodyWithoutGravityFallsAtHalfGAndTurns) {
  const std::string link = "<inertial><mass>1</mass><inertia><ixx>0.01</ixx><iyy>0.01</iyy><izz>0.01</izz></inertia>"
                           "</inertial>";
  const WorldDescription desc = test::groundWorld(
      "<model name='m'><pose>0 0 2 0 0 0</pose>"
      "<link name='a'><pose>-0.5 0 0 0 0 0</pose>" + link + "</link>"
      "<link name='b'><pose>0.5 0 0 0 0 0</pose><gravity>0</gravity>" + link + "</link>"
      "<joint name='weld' type='fixed'><parent>a</parent><child>b</child></joint></model>");
  PhysicsWorld world(physicsOptionsFor(desc));
  addWorldToPhysics(desc, &world, {});
  const PhysicsRobot& m = world.freeBody(world.freeBodyIndex("m"));
  const double t = stepFor(&world, 0.1);
  const Eigen::Vector3d a = m.linkPose("a").translation(), b = m.linkPose("b").translation();
  const double com_z = 0.5 * (a.z() + b.z());
  // Semi-implicit Euler: after n steps of dt at acceleration g/2 the drop is (g/2) dt^2 n(n+1)/2.
  const double n = std::round(t / world.dt()), dt = world.dt();
  EXPECT_NEAR(com_z, 2.0 - (9.8 / 2) * dt * dt * n * (n + 1) / 2, 1e-6);
  // Torque m g 0.5 about the COM, inertia 2 (0.01 + 1 0.5^2) + ... : a's side goes down.
  EXPECT_LT(a.z(), b.z() - 0.01);
}

// A robot's <gazebo reference> <turnGravityOff>: the same through the URDF path.
TEST(LinkGravity, ARobotLinkWithTurnGravityOffFloats) {
  const std::string urdf =
      "<robot name='r'><link name='base'><inertial><mass value='1'/><inertia ixx='0.01' iyy='0.01' izz='0.01' ixy='0' "
      "ixz='0' iyz='0'/></inertial><collision><geometry><box size='0.2 0.2 0.2'/></geometry></collision></link>"
      "<gazebo reference='base'><turnGravityOff>true</turnGravityOff></gazebo></robot>";
  const RobotModel model = loadRobotModel(urdf, "r.urdf", LoadOptions{});
  const WorldDescription desc = test::groundWorld("");
  PhysicsWorld world(physicsOptionsFor(desc));
  addWorldToPhysics(desc, &world, {});
  Eigen::Isometry3d X = Eigen::Isometry3d::Identity();
  X.translation().z() = 1.0;
  const PhysicsRobot& r = world.robot(addRobotModel(&world, model, X, "r"));
  stepFor(&world, 1.0);
  EXPECT_NEAR(r.basePose().translation().z(), 1.0, 1e-9);
}

}  // namespace
}  // namespace tianracer_sim
