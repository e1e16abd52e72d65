// Issue 40, point 2: a movable (non-static) flat mesh plate, as worlds saved from Gazebo's editor
// have, resting on the ground plane. Gazebo (ODE) keeps it there: dCollideTrimeshPlane
// (deps/opende/src/collision_trimesh_plane.cpp) makes a contact for every mesh vertex below the
// plane. The plate is two triangles (zero volume), written as an OBJ into a temp dir. Sim time only.
#include <gtest/gtest.h>

#include <stdlib.h>

#include <cmath>
#include <fstream>
#include <iostream>
#include <sstream>
#include <string>

#include "sim_test_support.h"
#include "tianracer_sim/sim/robot_physics.h"
#include "tianracer_sim/sim/world_physics.h"
#include "tianracer_sim/world/world.h"

namespace tianracer_sim {
namespace {

/// `text` written as `name` in a new temp dir; its path ("" when the dir cannot be made).
std::string writeMesh(const std::string& name, const std::string& text) {
  char tmpl[] = "/tmp/tianracer_plate_XXXXXX";
  if (::mkdtemp(tmpl) == nullptr) return "";
  const std::string file = std::string(tmpl) + "/" + name;
  std::ofstream(file) << text;
  return file;
}

/// A 2 x 2 m plate (scaled by `half` / 1 m) of two triangles at z = 0 of its link, facing up.
std::string writePlate(double half = 1.0) {
  std::ostringstream f;
  const double h = half;
  f << "v " << -h << " " << -h << " 0\nv " << h << " " << -h << " 0\nv " << h << " " << h
    << " 0\nv " << -h << " " << h << " 0\nf 1 2 3\nf 1 3 4\n";
  return writeMesh("plate.obj", f.str());
}

/// A closed 0.4 m cube mesh from z = 0 to 0.4 of its link, its faces outward.
std::string writeCube() {
  return writeMesh("cube.obj",
                   "v -0.2 -0.2 0\nv 0.2 -0.2 0\nv 0.2 0.2 0\nv -0.2 0.2 0\n"
                   "v -0.2 -0.2 0.4\nv 0.2 -0.2 0.4\nv 0.2 0.2 0.4\nv -0.2 0.2 0.4\n"
                   "f 1 3 2\nf 1 4 3\nf 5 6 7\nf 5 7 8\nf 1 2 6\nf 1 6 5\n"
                   "f 2 3 7\nf 2 7 6\nf 3 4 8\nf 3 8 7\nf 4 1 5\nf 4 5 8\n");
}

/// The ground plane and a 10 kg movable plate 1 cm above it.
WorldDescription plateWorld(const std::string& mesh) {
  return test::groundWorld(
      "<model name='plate'><pose>0 0 0.01 0 0 0</pose><link name='link'>"
      "<inertial><mass>10</mass><inertia><ixx>3.3</ixx><iyy>3.3</iyy><izz>6.7</izz></inertia></inertial>"
      "<collision name='c'><geometry><mesh><uri>" + mesh + "</uri></mesh></geometry></collision>"
      "<visual name='v'><geometry><mesh><uri>" + mesh + "</uri></mesh></geometry></visual>"
      "</link></model>");
}

TEST(MovablePlate, FlatMeshPlateRestsOnTheGroundPlane) {
  const std::string mesh = writePlate();
  ASSERT_FALSE(mesh.empty());
  const WorldDescription desc = plateWorld(mesh);
  PhysicsWorld world(physicsOptionsFor(desc));
  addWorldToPhysics(desc, &world, {});
  const PhysicsRobot& plate = world.freeBody(world.freeBodyIndex("plate"));
  double z_min = 1e9, z_end = 0.0;
  const long n = std::lround(3.0 / world.dt());
  for (long k = 0; k < n; ++k) {
    world.step();
    const double z = plate.linkPose("link").translation().z();
    z_min = std::min(z_min, z);
    z_end = z;
  }
  std::cout << "plate z after 3 s: " << z_end << " m (lowest " << z_min << " m)\n";
  // Resting on the plane: within a few mm of z = 0 (Bullet's margins), never below it by more.
  EXPECT_GT(z_min, -0.005);
  EXPECT_NEAR(z_end, 0.0, 0.005);
}

/// A 10 kg movable `mesh` dropped from `height` onto `ground` (an SDF model, no ground plane):
/// its z after 3 s, and the lowest z it reached.
struct Rest {
  double end, lowest;
};
Rest restOn(const std::string& ground, const std::string& mesh, double height = 0.01) {
  const WorldDescription desc = loadWorldString(
      "<sdf version='1.6'><world name='w'>" + ground +
          "<model name='plate'><pose>0 0 " + std::to_string(height) + " 0 0 0</pose><link name='link'>"
          "<inertial><mass>10</mass><inertia><ixx>3.3</ixx><iyy>3.3</iyy><izz>6.7</izz></inertia></inertial>"
          "<collision name='c'><geometry><mesh><uri>" + mesh + "</uri></mesh></geometry></collision>"
          "</link></model></world></sdf>",
      "test.world", ".");
  PhysicsWorld world(physicsOptionsFor(desc));
  addWorldToPhysics(desc, &world, {});
  const PhysicsRobot& plate = world.freeBody(world.freeBodyIndex("plate"));
  Rest r{0.0, 1e9};
  for (long k = 0; k < std::lround(3.0 / world.dt()); ++k) {
    world.step();
    r.end = plate.linkPose("link").translation().z();
    r.lowest = std::min(r.lowest, r.end);
  }
  return r;
}

/// A static model whose collision is `mesh` at z = 0.
std::string staticMeshGround(const std::string& mesh) {
  return "<model name='g'><static>true</static><link name='l'><collision name='c'><geometry><mesh><uri>" +
         mesh + "</uri></mesh></geometry></collision></link></model>";
}

TEST(MovablePlate, FlatMeshPlateRestsOnAStaticBox) {
  const std::string mesh = writePlate();
  ASSERT_FALSE(mesh.empty());
  const Rest on_box = restOn(
      "<model name='g'><static>true</static><pose>0 0 -0.5 0 0 0</pose><link name='l'><collision name='c'>"
      "<geometry><box><size>10 10 1</size></box></geometry></collision></link></model>", mesh);
  std::cout << "plate z after 3 s on a static box " << on_box.end << " m\n";
  EXPECT_NEAR(on_box.end, 0.0, 0.005);
}

// A movable mesh on a static mesh: ODE collides the two trimeshes triangle by triangle
// (deps/opende/src/collision_trimesh_trimesh_new.cpp, FindTriangleTriangleCollision: the other
// triangle clipped by this one's edges, the deepest points against its plane, the direction of
// least depth), Bullet's GImpact the same way (btPrimitiveTriangle::find_triangle_collision_clip_method).
// Before, the flat plate fell through a flat static ground mesh (AABBs of zero thickness).
TEST(MovablePlate, FlatMeshPlateRestsOnAStaticMesh) {
  const std::string plate = writePlate(), ground = writePlate(5.0);
  ASSERT_FALSE(plate.empty() || ground.empty());
  const Rest r = restOn(staticMeshGround(ground), plate);
  std::cout << "plate on a static flat mesh: z after 3 s " << r.end * 1e3 << " mm, lowest " << r.lowest * 1e3
            << " mm\n";
  EXPECT_NEAR(r.end, 0.0, 0.001);
  EXPECT_GT(r.lowest, -0.001);
  // Dropped from 0.5 m it meets the ground at 3.1 m/s (3 mm a step) and stays on it.
  const Rest dropped = restOn(staticMeshGround(ground), plate, 0.5);
  std::cout << "dropped from 0.5 m: z after 3 s " << dropped.end * 1e3 << " mm, lowest " << dropped.lowest * 1e3
            << " mm\n";
  EXPECT_NEAR(dropped.end, 0.0, 0.001);
  EXPECT_GT(dropped.lowest, -0.005);
}

TEST(MovablePlate, ClosedMeshRestsOnAStaticMesh) {
  const std::string cube = writeCube(), ground = writePlate(5.0);
  ASSERT_FALSE(cube.empty() || ground.empty());
  const Rest r = restOn(staticMeshGround(ground), cube);
  std::cout << "cube mesh on a static flat mesh: z after 3 s " << r.end * 1e3 << " mm, lowest " << r.lowest * 1e3
            << " mm\n";
  EXPECT_NEAR(r.end, 0.0, 0.001);
  EXPECT_GT(r.lowest, -0.001);
}

// The acceptance test of issue 40: the tianracer drives 60 s (sim time) on a flat movable floor
// mesh (30 x 30 m, 10 kg); the floor stays within 1 mm of its resting height, the car level.
void driveSixtySecondsOnTheFloor(const WorldDescription& desc) {
  PhysicsWorld world(physicsOptionsFor(desc));
  addWorldToPhysics(desc, &world, {});
  static const RobotModel model = test::loadTianracer();
  Eigen::Isometry3d X = Eigen::Isometry3d::Identity();
  X.translation() = Eigen::Vector3d(-5.0, 0.0, 0.01 + test::kSpawnZ);
  PhysicsRobot& car = world.robot(addRobotModel(&world, model, X, "tianracer"));
  const PhysicsRobot& plate = world.freeBody(world.freeBodyIndex("plate"));
  const int lr = car.jointIndex("left_rear_wheel_joint"), rr = car.jointIndex("right_rear_wheel_joint");
  const int hinges[2] = {car.jointIndex("left_steering_hinge_joint"),
                         car.jointIndex("right_steering_hinge_joint")};
  double prev[2] = {0.0, 0.0};
  const long settle = 1000, n = std::lround(60.0 / world.dt());
  double z0 = 0.0, drift = 0.0, tilt = 0.0;
  for (long k = 0; k < settle + n; ++k) {
    for (int h = 0; h < 2; ++h) {  // hinges held straight (effort_controllers' PD gains)
      const double e = -car.jointPosition(hinges[h]);
      car.setJointEffort(hinges[h], 20.0 * e + 0.2 * (k == 0 ? 0.0 : (e - prev[h]) / world.dt()));
      prev[h] = e;
    }
    const double omega = k < settle ? 0.0 : 0.2 / test::kWheelRadius;
    car.setJointVelocityTarget(lr, omega);
    car.setJointVelocityTarget(rr, omega);
    world.step();
    const double z = plate.linkPose("link").translation().z();
    if (k == settle) z0 = z;
    if (k < settle) continue;
    drift = std::max(drift, std::abs(z - z0));
    tilt = std::max(tilt, std::acos(std::min(1.0, car.basePose().linear()(2, 2))));
  }
  const Eigen::Vector3d end = car.basePose().translation();
  std::cout << "floor rest z " << z0 * 1e3 << " mm, max drift " << drift * 1e3 << " mm over 60 s; car max tilt "
            << tilt << " rad, ends at " << end.transpose() << "\n";
  EXPECT_LT(drift, 0.001);
  EXPECT_LT(tilt, 0.02);
  EXPECT_GT(end.x(), 5.0);  // it drove (about 12 m at 0.2 m/s), on the floor, not beside it
  EXPECT_GT(end.z(), 0.0);
}

TEST(MovablePlate, CarDrivesSixtySecondsOnAFlatMovableFloor) {
  const std::string mesh = writePlate(15.0);
  ASSERT_FALSE(mesh.empty());
  driveSixtySecondsOnTheFloor(plateWorld(mesh));
}

// The same floor resting on a static flat ground mesh instead of the ground plane.
TEST(MovablePlate, CarDrivesSixtySecondsOnAFlatMovableFloorOnAStaticMesh) {
  const std::string mesh = writePlate(15.0), ground = writePlate(20.0);
  ASSERT_FALSE(mesh.empty() || ground.empty());
  driveSixtySecondsOnTheFloor(loadWorldString(
      "<sdf version='1.6'><world name='w'>" + staticMeshGround(ground) +
          "<model name='plate'><pose>0 0 0.01 0 0 0</pose><link name='link'>"
          "<inertial><mass>10</mass><inertia><ixx>3.3</ixx><iyy>3.3</iyy><izz>6.7</izz></inertia></inertial>"
          "<collision name='c'><geometry><mesh><uri>" + mesh + "</uri></mesh></geometry></collision>"
          "</link></model></world></sdf>",
      "test.world", "."));
}

}  // namespace
}  // namespace tianracer_sim
