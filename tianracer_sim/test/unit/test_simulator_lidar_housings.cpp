// Lidars inside their own housing collisions (test/data/urdf/lidar_housings.urdf: a 2D ray
// lidar, a gpu_ray lidar whose housing is its parent link's collision, a VLP-16-style 3D lidar)
// see the world through them, because rays start at <range><min> as in Gazebo
// (gazebo-classic physics/MultiRayShape.cc). Every range is checked against the exact distance
// from the sensor to the wall or the ground, for rays from range_min.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <string>
#include <vector>

#include "tianracer_sim/plugins/ray/sim_ray.h"
#include "tianracer_sim/simulator/simulator.h"

#include "sim_test_support.h"

namespace tianracer_sim {
namespace {

constexpr double kInf = std::numeric_limits<double>::infinity();

// The first surface of test::groundWithWall()'s wall (x 1.9 .. 2.1, y -2 .. 2, z 0 .. 1) or the
// ground at t >= t_min along o + t d (a ray starting inside the wall would see its far side;
// none does here). Rays hit collisions only: the wall's visual is not seen.
double exactRange(const Eigen::Vector3d& o, const Eigen::Vector3d& d, double t_min) {
  const Eigen::Vector3d lo(1.9, -2.0, 0.0), hi(2.1, 2.0, 1.0);
  double t0 = -kInf, t1 = kInf;
  bool miss = false;
  for (int k = 0; k < 3; ++k) {
    if (d[k] == 0.0) {
      miss = miss || o[k] < lo[k] || o[k] > hi[k];
      continue;
    }
    double a = (lo[k] - o[k]) / d[k], b = (hi[k] - o[k]) / d[k];
    if (a > b) std::swap(a, b);
    t0 = std::max(t0, a);
    t1 = std::min(t1, b);
  }
  double best = kInf;
  if (!miss && t0 <= t1 && t1 >= t_min) best = t0 >= t_min ? t0 : t1;
  if (d.z() != 0.0) {
    const double t = -o.z() / d.z();
    if (t >= t_min) best = std::min(best, t);
  }
  return best;
}

struct Checked {
  int rays = 0, wall_or_ground = 0;
};

// Compares a lidar's last scan with exactRange() from its current pose (the robot is at rest).
Checked checkScan(const Simulator& sim, const SimLidar& lidar) {
  const RaySensorConfig& c = lidar.config();
  const Eigen::Isometry3d X_WS = sim.linkPose(lidar.link()) * c.X_LS;
  const std::vector<float>& r = lidar.ranges();
  const std::vector<Eigen::Vector3d>& dirs = lidar.directions();
  Checked out;
  EXPECT_EQ(r.size(), dirs.size());
  for (std::size_t k = 0; k < r.size() && k < dirs.size(); ++k) {
    const double t = exactRange(X_WS.translation(), X_WS.linear() * dirs[k], c.range_min);
    ++out.rays;
    if (c.velodyne) {
      // The cloud keeps max(min_range, range min) < r < min(max_range, range max), else NaN.
      const bool kept = t > std::max(c.cloud_min_range, c.range_min) &&
                        t < std::min(c.cloud_max_range, c.range_max);
      if (!kept) {
        EXPECT_TRUE(std::isnan(r[k])) << c.name << " ray " << k << ": " << r[k];
        continue;
      }
    } else if (t >= c.range_max) {
      EXPECT_EQ(r[k], std::numeric_limits<float>::infinity()) << c.name << " ray " << k;
      continue;
    }
    EXPECT_NEAR(r[k], t, 3e-3) << c.name << " ray " << k;
    ++out.wall_or_ground;
  }
  return out;
}

TEST(SimulatorLidarHousings, LidarsInsideTheirHousingsSeeTheWorld) {
  Simulator sim(test::groundWithWall(), {});
  RobotSpawn spawn;
  spawn.name = "housings";
  spawn.model = loadRobotModelFile(TEST_DATA_DIR "/urdf/lidar_housings.urdf", {});
  spawn.drop_to_ground = true;
  const ModelId id = sim.addRobot(std::move(spawn));
  sim.step(1000);  // at rest on the ground; each lidar has scanned (10 Hz)

  const auto* laser = dynamic_cast<const SimLidar*>(sim.findSensor(id, "laser"));
  const auto* gpu = dynamic_cast<const SimLidar*>(sim.findSensor(id, "gpu_laser"));
  const auto* velodyne = dynamic_cast<const SimLidar*>(sim.findSensor(id, "velodyne-VLP16"));
  ASSERT_NE(laser, nullptr);
  ASSERT_NE(gpu, nullptr);
  ASSERT_NE(velodyne, nullptr);
  ASSERT_GT(laser->stat().renders, 0u);

  // Straight ahead each sees the wall's face at x = 1.9: the 2D lidars from x = 0.1.
  EXPECT_NEAR(laser->ranges()[180], 1.8, 3e-3);
  EXPECT_NEAR(gpu->ranges()[180], 1.8, 3e-3);
  // The 3D lidar (x = -0.1, ring 8 at +1 deg): 2.0 / cos(1 deg), a point of the cloud.
  const int ring8_ahead = 8 * velodyne->config().samples + 180;
  EXPECT_NEAR(velodyne->ranges()[ring8_ahead], 2.0 / std::cos(velodyne->config().verticalAngle(8)),
              3e-3);

  // Every ray: the wall or the ground where there is one beyond range_min, nothing else.
  const Checked a = checkScan(sim, *laser);
  const Checked b = checkScan(sim, *gpu);
  const Checked v = checkScan(sim, *velodyne);
  EXPECT_EQ(a.rays, 361);
  EXPECT_GT(a.wall_or_ground, 80);  // the wall spans about +-48 deg from 1.8 m
  EXPECT_GT(b.wall_or_ground, 80);
  EXPECT_EQ(v.rays, 16 * 361);
  EXPECT_GT(v.wall_or_ground, 1000);  // wall rings ahead and the ground at 1.1 - 1.6 m all round
}

}  // namespace
}  // namespace tianracer_sim
