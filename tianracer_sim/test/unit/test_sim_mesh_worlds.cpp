// Gazebo-style mesh content through the ROS-free core (world loader, world physics, Simulation,
// ray caster): a static Z_UP course drawn in millimetres with a node matrix, placed by an
// <include> with a pose, carries the car and its walls stop the lidar; a non-static cone drawn
// in inches and scaled 10x by its SDF stands upright on its base.
#include <gtest/gtest.h>

#include <cmath>
#include <string>
#include <vector>

#include "sim_test_support.h"
#include "tianracer_sim/lidar/ray_caster.h"
#include "tianracer_sim/scene/scene.h"
#include "tianracer_sim/sim/world_physics.h"
#include "tianracer_sim/world/world.h"

namespace tianracer_sim {
namespace {

const std::string kModels = std::string(TEST_DATA_DIR) + "/worlds/models";

WorldDescription worldOf(const std::string& body) {
  WorldLoadOptions options;
  options.model_paths = {kModels};
  options.strict = true;  // nothing may be left out here
  return loadWorldString("<sdf version='1.6'><world name='w'>" + body + "</world></sdf>",
                         "test.world", kModels, options);
}

Eigen::Isometry3d pose(double x, double y, double z, double yaw) {
  Eigen::Isometry3d X = Eigen::Isometry3d::Identity();
  X.translation() = Eigen::Vector3d(x, y, z);
  X.linear() = Eigen::AngleAxisd(yaw, Eigen::Vector3d::UnitZ()).toRotationMatrix();
  return X;
}

double tiltOf(const Eigen::Isometry3d& X) {
  return std::acos(std::min(1.0, (X.linear() * Eigen::Vector3d::UnitZ()).z()));
}

/// Height of base_link when the parked car has settled on `world` for 2 s, spawned above `X`.
Eigen::Isometry3d settledCar(const WorldDescription& world, const Eigen::Isometry3d& X) {
  Simulation sim(physicsOptionsFor(world));
  addWorldToPhysics(world, &sim.physics(), WarningSink());
  RobotConfig car;
  car.name = "tianracer";
  car.model = test::loadTianracer();
  car.X_WB_spawn = X;
  car.X_WB_spawn.translation().z() += 0.02;
  SimRobot& robot = sim.addRobot(car);
  while (sim.time() < 2.0) sim.step();
  return sim.physics().robot(robot.id).basePose();
}

TEST(MeshWorlds, CarStandsOnAZUpCourseWithANodeMatrixAndTheLidarSeesItsWalls) {
  // The course's floor is its model frame's z = 0 plane: put 0.5 m up, turned 0.3 rad, with no
  // ground plane under it. Misread (Y_UP, or the node matrix lost), the car falls.
  const Eigen::Isometry3d X_WC = pose(3.0, -1.0, 0.5, 0.3);
  const WorldDescription course =
      worldOf("<include><uri>model://zup_course</uri><pose>3 -1 0.5 0 0 0.3</pose></include>");
  ASSERT_EQ(course.models.size(), 1u);
  const WorldDescription ground = worldOf("<include><uri>model://ground_plane</uri></include>");
  const Eigen::Isometry3d on_ground = settledCar(ground, pose(0, 0, 0, 0.3));
  const Eigen::Isometry3d on_course = settledCar(course, X_WC);
  EXPECT_NEAR(on_course.translation().z(), 0.5 + on_ground.translation().z(), 0.002);
  EXPECT_NEAR((on_course.translation() - X_WC.translation()).head<2>().norm(), 0.0, 0.01);
  EXPECT_LT(tiltOf(on_course), 0.01);

  // The lidar's scan plane, 0.1 m above the floor at the car: every beam of a full turn hits the
  // inner face of a wall (|x|, |y| = 1.9 m in the course frame) within 5 mm.
  Scene scene;
  addToScene(course, scene);
  RayCaster caster;
  caster.update(scene);
  const Eigen::Vector3d o_W = on_course.translation() + Eigen::Vector3d(0, 0, 0.1);
  const Eigen::Vector3d o_C = X_WC.inverse() * o_W;
  std::vector<Eigen::Vector3f> dirs;
  std::vector<double> expected;
  for (int k = 0; k < 360; ++k) {
    const double a = 2.0 * M_PI * k / 360;
    const Eigen::Vector3d d_C(std::cos(a), std::sin(a), 0.0);
    dirs.push_back((X_WC.linear() * d_C).cast<float>());
    double t = INFINITY;
    for (int i = 0; i < 2; ++i) {
      if (std::abs(d_C[i]) > 1e-9) t = std::min(t, ((d_C[i] > 0 ? 1.9 : -1.9) - o_C[i]) / d_C[i]);
    }
    expected.push_back(t);
  }
  std::vector<float> ranges(dirs.size());
  caster.castRays(o_W, dirs, 0.0f, 10.0f, ranges.data());
  for (std::size_t k = 0; k < dirs.size(); ++k) {
    ASSERT_NEAR(ranges[k], expected[k], 0.005) << "beam " << k << " deg";
  }
}

TEST(MeshWorlds, InchConeScaledTenTimesStandsUprightOnItsBase) {
  // The cone's base is its model origin (z = 0); radius 1 in x 10 = 0.254 m, height 1.016 m.
  const WorldDescription w = worldOf("<include><uri>model://ground_plane</uri></include>"
                                     "<include><uri>model://inch_cone</uri></include>");
  ASSERT_EQ(w.models.size(), 1u);
  ASSERT_FALSE(w.models[0].is_static);
  Simulation sim(physicsOptionsFor(w));
  addWorldToPhysics(w, &sim.physics(), WarningSink());
  const PhysicsRobot* cone = sim.findModel("inch_cone");
  ASSERT_NE(cone, nullptr);
  double worst_z = 0.0, worst_tilt = 0.0, worst_xy = 0.0;
  while (sim.time() < 30.0) {
    sim.step();
    if (sim.stepCount() % 10 != 0) continue;
    const Eigen::Isometry3d X = cone->basePose();
    worst_z = std::max(worst_z, std::abs(X.translation().z()));
    worst_tilt = std::max(worst_tilt, tiltOf(X));
    worst_xy = std::max(worst_xy, X.translation().head<2>().norm());
  }
  EXPECT_LT(worst_z, 0.005);
  EXPECT_LT(worst_tilt, 0.01);
  EXPECT_LT(worst_xy, 0.005);
}

}  // namespace
}  // namespace tianracer_sim
