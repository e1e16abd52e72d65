// Issue 40, point 2: a movable (non-static) flat mesh plate, as worlds saved from Gazebo's editor
// have, resting on the ground plane. Gazebo (ODE) keeps it there: dCollideTrimeshPlane
// (deps/opende/src/collision_trimesh_plane.cpp) makes a contact for every mesh vertex below the
// plane. The plate is two triangles (zero volume), written as an OBJ into a temp dir. Sim time only.
#include <gtest/gtest.h>

#include <stdlib.h>

#include <cmath>
#include <fstream>
#include <iostream>
#include <string>

#include "sim_test_support.h"
#include "tianracer_sim/sim/world_physics.h"
#include "tianracer_sim/world/world.h"

namespace tianracer_sim {
namespace {

/// A 2 x 2 m plate of two triangles at z = 0 of its link, written as plate.obj in a new temp dir.
std::string writePlate() {
  char tmpl[] = "/tmp/tianracer_plate_XXXXXX";
  if (::mkdtemp(tmpl) == nullptr) return "";
  const std::string file = std::string(tmpl) + "/plate.obj";
  std::ofstream f(file);
  f << "v -1 -1 0\nv 1 -1 0\nv 1 1 0\nv -1 1 0\nf 1 2 3\nf 1 3 4\n";
  return file;
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

}  // namespace
}  // namespace tianracer_sim
