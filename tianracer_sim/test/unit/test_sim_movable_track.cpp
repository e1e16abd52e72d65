// Issue 24's movable floor: a non-static track whose floor and walls are two links with no joint
// (DAE/STL collisions, 1,665 kg each, saved while settling; test/data/worlds/movable_track).
// The shipped tianracer drives across it exactly as across the same track made static: Gazebo
// gives two separate bodies with concave triangle-mesh collisions, and so do we (a convex hull of
// the walls would be a block around the car). Sim time only; the figures are printed.
#include <gtest/gtest.h>

#include <cmath>
#include <iostream>
#include <string>

#pragma GCC diagnostic push
#pragma GCC diagnostic ignored "-Wunused-parameter"
#include <btBulletCollisionCommon.h>
#pragma GCC diagnostic pop

#include "sim_test_support.h"
#include "tianracer_sim/sim/robot_physics.h"
#include "tianracer_sim/sim/world_physics.h"
#include "tianracer_sim/world/world.h"

namespace tianracer_sim {
namespace {

const std::string kTrack = std::string(TEST_DATA_DIR) + "/worlds/movable_track/movable_track.world";

struct DriveResult {
  double max_tilt = 0.0;    // rad, between the car's z axis and the world's
  double mean_speed = 0.0;  // m/s over the last second
  double max_z = 0.0;       // m, base_link
  double floor_moved = 0.0, walls_moved = 0.0;  // m, since the start of the drive
  Eigen::Vector3d end = Eigen::Vector3d::Zero();
};

/// The car on the track, rear wheels at v / r, hinges held straight by a PD on their efforts
/// (effort_controllers' gains of the shipped YAML); 0.5 s to settle, then `seconds` of driving.
DriveResult drive(bool track_static, double v, double seconds) {
  WorldDescription desc = loadWorldFile(kTrack);
  desc.models.at(0).is_static = track_static;
  PhysicsWorld world(physicsOptionsFor(desc));
  addWorldToPhysics(desc, &world, {});
  static const RobotModel model = test::loadTianracer();
  Eigen::Isometry3d X = Eigen::Isometry3d::Identity();
  X.translation() = Eigen::Vector3d(-1.5, 0.3, 0.02 + test::kSpawnZ);  // on the floor
  PhysicsRobot& car = world.robot(addRobotModel(&world, model, X, "tianracer"));
  const int lr = car.jointIndex("left_rear_wheel_joint"), rr = car.jointIndex("right_rear_wheel_joint");
  const int hinges[2] = {car.jointIndex("left_steering_hinge_joint"),
                         car.jointIndex("right_steering_hinge_joint")};
  double prev[2] = {0.0, 0.0};
  bool first = true;
  const PhysicsRobot* track = track_static ? nullptr : &world.freeBody(world.freeBodyIndex("track"));
  DriveResult run;
  Eigen::Vector3d floor0 = Eigen::Vector3d::Zero(), walls0 = Eigen::Vector3d::Zero();
  double speed_sum = 0.0;
  int speed_n = 0;
  const long settle = 500, n = std::lround(seconds / world.dt());
  for (long k = 0; k < settle + n; ++k) {
    for (int h = 0; h < 2; ++h) {
      const double e = -car.jointPosition(hinges[h]);
      car.setJointEffort(hinges[h], 20.0 * e + 0.2 * (first ? 0.0 : (e - prev[h]) / world.dt()));
      prev[h] = e;
    }
    first = false;
    const double omega = k < settle ? 0.0 : v / test::kWheelRadius;
    car.setJointVelocityTarget(lr, omega);
    car.setJointVelocityTarget(rr, omega);
    world.step();
    if (k == settle && track) {
      floor0 = track->linkPose("floor").translation();
      walls0 = track->linkPose("walls").translation();
    }
    if (k < settle) continue;
    const Eigen::Isometry3d X_WB = car.basePose();
    run.max_tilt = std::max(run.max_tilt, std::acos(std::min(1.0, X_WB.linear()(2, 2))));
    run.max_z = std::max(run.max_z, X_WB.translation().z());
    if (k >= settle + n - 1000) {
      speed_sum += car.baseTwist().linear.head<2>().norm();
      ++speed_n;
    }
  }
  run.mean_speed = speed_sum / speed_n;
  run.end = car.basePose().translation();
  if (track) {
    run.floor_moved = (track->linkPose("floor").translation() - floor0).norm();
    run.walls_moved = (track->linkPose("walls").translation() - walls0).norm();
  }
  return run;
}

TEST(MovableTrack, IsTwoBodiesWithConcaveMeshes) {
  const WorldDescription desc = loadWorldFile(kTrack);
  PhysicsWorld world(physicsOptionsFor(desc));
  std::vector<std::string> warnings;
  addWorldToPhysics(desc, &world, [&](const std::string& w) { warnings.push_back(w); });
  EXPECT_TRUE(warnings.empty());
  const PhysicsRobot& track = world.freeBody(world.freeBodyIndex("track"));
  ASSERT_EQ(track.tree().bodies.size(), 2u);
  EXPECT_DOUBLE_EQ(track.tree().bodies[0].mass.mass, 1665.0);
  EXPECT_DOUBLE_EQ(track.tree().bodies[1].mass.mass, 1665.0);
  // Both colliders keep their triangles (a GImpact mesh in the body's compound).
  for (const char* link : {"floor", "walls"}) {
    const btCollisionObject* o = track.collisionObject(link);
    ASSERT_NE(o, nullptr);
    ASSERT_EQ(o->getCollisionShape()->getShapeType(), COMPOUND_SHAPE_PROXYTYPE);
    const auto* compound = static_cast<const btCompoundShape*>(o->getCollisionShape());
    ASSERT_EQ(compound->getNumChildShapes(), 1);
    EXPECT_EQ(compound->getChildShape(0)->getShapeType(), GIMPACT_SHAPE_PROXYTYPE) << link;
  }
  // Saved while settling: the floor slightly sunk, the walls slightly up; both come to rest on
  // the ground within a second.
  for (int k = 0; k < 1000; ++k) world.step();
  std::cout << "[movable track] settled: floor at z " << track.linkPose("floor").translation().z()
            << ", walls at z " << track.linkPose("walls").translation().z() << "\n";
  EXPECT_NEAR(track.linkPose("floor").translation().z(), 0.0, 5e-4);
  EXPECT_NEAR(track.linkPose("walls").translation().z(), 0.0, 5e-4);
}

TEST(MovableTrack, CarDrivesOnItAsOnTheStaticTrack) {
  const double v = 1.0, seconds = 3.0;
  const DriveResult fixed = drive(true, v, seconds);
  const DriveResult moving = drive(false, v, seconds);
  for (const auto& [name, r] : {std::make_pair("static track", fixed), std::make_pair("movable track", moving)}) {
    std::cout << "[car on the " << name << ", " << v << " m/s] max tilt " << r.max_tilt
              << " rad, max base z " << r.max_z << " m, mean speed (last 1 s) " << r.mean_speed
              << " m/s, ends at " << r.end.transpose() << "; floor moved " << r.floor_moved
              << " m, walls " << r.walls_moved << " m\n";
  }
  std::cout << "[movable vs static] speed " << 100.0 * (moving.mean_speed / fixed.mean_speed - 1.0)
            << " %, end point " << (moving.end - fixed.end).norm() << " m apart\n";
  EXPECT_LT(moving.max_tilt, 0.02);
  EXPECT_LT(fixed.max_tilt, 0.02);
  EXPECT_NEAR(moving.mean_speed, fixed.mean_speed, 0.01 * fixed.mean_speed);
  EXPECT_NEAR(fixed.mean_speed, v, 0.01 * v);
  EXPECT_LT(moving.max_z, 0.02 + 0.02);  // stays on the floor (base_link ~9.5 mm above it)
  EXPECT_LT(moving.floor_moved, 1e-3);   // 1,665 kg: the car does not shove it
  EXPECT_LT(moving.walls_moved, 1e-3);
}

}  // namespace
}  // namespace tianracer_sim
