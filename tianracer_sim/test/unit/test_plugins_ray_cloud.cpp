// The 3D lidar (vertical samples > 1): ring and beam angles exactly as configured, and every
// range within 1 mm of the exact distance to a closed room (noise off); the cloud range model.
#include <cmath>
#include <limits>
#include <random>
#include <vector>

#include <gtest/gtest.h>

#include "tianracer_sim/lidar/ray_caster.h"
#include "tianracer_sim/plugins/ray/ray_sensor.h"

namespace tianracer_sim {
namespace {

constexpr double kX0 = -2.0, kX1 = 3.0, kY0 = -1.5, kY1 = 2.5;  // inner faces of the room

RaySensorConfig velodyne16() {
  RaySensorConfig c;
  c.name = "velodyne";
  c.link = "base";
  c.update_rate = 10;
  c.samples = 1800;
  c.min_angle = -M_PI;
  c.max_angle = M_PI;
  c.vertical_samples = 16;
  c.vertical_min_angle = -0.2617993878;
  c.vertical_max_angle = 0.2617993878;
  c.range_min = 0.3;
  c.range_max = 100.0;
  c.velodyne = true;
  c.has_ros_plugin = true;
  return c;
}

SceneItem box(int body, double x, double y, const Eigen::Vector3d& size) {
  SceneItem it;
  it.body = body;
  it.X_BS.translation() = Eigen::Vector3d(x, y, 0.5);
  it.shape.type = ShapeType::kBox;
  it.shape.size = size;
  it.collision = true;
  it.visual = false;
  return it;
}

/// Walls 0.1 m thick and 20 m tall: every ray of a +-15 deg fan hits one of them.
Scene room() {
  Scene scene;
  SceneBody b;
  b.name = "room::link";
  b.model = "room";
  const int body = scene.addBody(b);
  const double cx = (kX0 + kX1) / 2, cy = (kY0 + kY1) / 2;
  const double w = kX1 - kX0 + 0.2, h = kY1 - kY0 + 0.2;
  scene.items.push_back(box(body, cx, kY1 + 0.05, {w, 0.1, 20.0}));
  scene.items.push_back(box(body, cx, kY0 - 0.05, {w, 0.1, 20.0}));
  scene.items.push_back(box(body, kX1 + 0.05, cy, {0.1, h, 20.0}));
  scene.items.push_back(box(body, kX0 - 0.05, cy, {0.1, h, 20.0}));
  return scene;
}

double exactRange(const Eigen::Vector3d& o, const Eigen::Vector3d& d) {
  double t = std::numeric_limits<double>::infinity();
  if (d.x() > 0) t = std::min(t, (kX1 - o.x()) / d.x());
  if (d.x() < 0) t = std::min(t, (kX0 - o.x()) / d.x());
  if (d.y() > 0) t = std::min(t, (kY1 - o.y()) / d.y());
  if (d.y() < 0) t = std::min(t, (kY0 - o.y()) / d.y());
  return t;
}

TEST(LidarCloud, RingAndBeamAnglesAreTheConfiguredOnes) {
  const RaySensorConfig c = velodyne16();
  EXPECT_DOUBLE_EQ(c.verticalAngle(0), c.vertical_min_angle);
  EXPECT_DOUBLE_EQ(c.verticalAngle(15), c.vertical_max_angle);
  RayCaster caster;
  Scene scene = room();
  RaySensor sensor(c);
  sensor.scan(caster, scene, Eigen::Isometry3d::Identity());
  const std::vector<Eigen::Vector3d>& d = sensor.directions();
  ASSERT_EQ(d.size(), 16u * 1800u);
  for (int j = 0; j < 16; ++j) {
    for (int i : {0, 1, 900, 1799}) {
      const Eigen::Vector3d& u = d[j * 1800 + i];
      EXPECT_NEAR(u.norm(), 1.0, 1e-15);
      EXPECT_NEAR(std::asin(u.z()), c.verticalAngle(j), 1e-15) << j << " " << i;
      EXPECT_NEAR(std::atan2(u.y(), u.x()), c.angle(i) == M_PI ? M_PI : c.angle(i), 1e-15);
    }
  }
  // The limits themselves.
  EXPECT_NEAR(std::asin(d.front().z()), c.vertical_min_angle, 1e-15);
  EXPECT_NEAR(std::asin(d.back().z()), c.vertical_max_angle, 1e-15);
  EXPECT_NEAR(std::atan2(d.front().y(), d.front().x()), -M_PI, 1e-15);
}

TEST(LidarCloud, RangesMatchAnAnalyticRoom) {
  const RaySensorConfig c = velodyne16();
  RayCaster caster;
  Scene scene = room();
  RaySensor sensor(c);
  Eigen::Isometry3d X_WS = Eigen::Isometry3d::Identity();
  X_WS.linear() = (Eigen::AngleAxisd(0.4, Eigen::Vector3d::UnitZ()) *
                   Eigen::AngleAxisd(0.05, Eigen::Vector3d::UnitY()))
                      .toRotationMatrix();
  X_WS.translation() = Eigen::Vector3d(0.3, 0.2, 0.5);
  const std::vector<float>& r = sensor.scan(caster, scene, X_WS);
  ASSERT_EQ(r.size(), 16u * 1800u);
  double worst = 0.0;
  for (std::size_t k = 0; k < r.size(); ++k) {
    const double ref = exactRange(X_WS.translation(), X_WS.linear() * sensor.directions()[k]);
    ASSERT_TRUE(std::isfinite(r[k])) << k;
    worst = std::max(worst, std::abs(r[k] - ref));
  }
  EXPECT_LT(worst, 1e-3);
}

// A real 3D lidar model (velodyne_description's VLP-16) puts the sensor 37.7 mm above the base
// of its housing collision, a cylinder of radius 51.6 mm and height 71.7 mm, with <range><min>
// 0.9 and the plugin's min_range 0.9. Rays start at range_min, as Gazebo's do, so every ray
// passes the housing and the cloud is the room (before: every ray hit the housing, no point).
TEST(LidarCloud, ALidarInsideItsHousingSeesTheRoom) {
  RaySensorConfig c = velodyne16();
  c.range_min = 0.9;
  c.cloud_min_range = 0.9;
  c.cloud_max_range = 130.0;
  RayCaster caster;
  Scene scene = room();
  SceneBody lidar;
  lidar.name = "robot::velodyne_base_link";
  lidar.model = "robot";
  lidar.is_static = false;
  lidar.X_WB.translation() = Eigen::Vector3d(0.3, 0.2, 0.5);
  const int b = scene.addBody(lidar);
  SceneItem housing;
  housing.body = b;
  housing.X_BS.translation() = Eigen::Vector3d(0, 0, 0.03585);
  housing.shape.type = ShapeType::kCylinder;
  housing.shape.radius = 0.0516;
  housing.shape.length = 0.0717;
  housing.collision = true;
  housing.visual = false;
  scene.items.push_back(housing);
  RaySensor sensor(c);
  Eigen::Isometry3d X_BS = Eigen::Isometry3d::Identity();
  X_BS.translation() = Eigen::Vector3d(0, 0, 0.0377);  // velodyne_base_scan_joint
  const Eigen::Isometry3d X_WS = scene.bodies[b].X_WB * X_BS;
  const std::vector<float>& r = sensor.scan(caster, scene, X_WS);
  ASSERT_EQ(r.size(), 16u * 1800u);
  double worst = 0.0;
  for (std::size_t k = 0; k < r.size(); ++k) {
    const double ref = exactRange(X_WS.translation(), sensor.directions()[k]);
    ASSERT_TRUE(std::isfinite(r[k])) << "ray " << k << " has no point";
    worst = std::max(worst, std::abs(r[k] - ref));
  }
  EXPECT_LT(worst, 1e-3);
  // A housing that reaches past range_min (radius 1 m) is what the rays see, from inside: its
  // wall at 1 m is kept, as in Gazebo.
  scene.items.back().shape.radius = 1.0;
  RayCaster rebuilt;  // a caster rebuilds on added bodies or items, not on changed shapes
  const std::vector<float>& inside = sensor.scan(rebuilt, scene, X_WS);
  EXPECT_NEAR(inside[8 * 1800 + 900], 1.0 / std::cos(c.verticalAngle(8)), 1e-4);
}

TEST(LidarCloud, RangeModel) {
  RaySensorConfig c = velodyne16();
  c.cloud_min_range = 0.9;
  c.cloud_max_range = 2.0;
  std::mt19937_64 rng(3);
  const float inf = std::numeric_limits<float>::infinity();
  std::vector<float> r = {0.5f, 0.95f, 1.5f, 2.0f, 2.5f, inf};
  applyCloudRangeModel(c, rng, r.data(), static_cast<int>(r.size()));
  EXPECT_TRUE(std::isnan(r[0]));  // below min_range
  EXPECT_FLOAT_EQ(r[1], 0.95f);
  EXPECT_FLOAT_EQ(r[2], 1.5f);
  EXPECT_TRUE(std::isnan(r[3]));  // the upper limit is exclusive
  EXPECT_TRUE(std::isnan(r[4]));
  EXPECT_TRUE(std::isnan(r[5]));  // no hit: no point
  // gaussianNoise: its standard deviation over 1e4 draws.
  c.cloud_noise = 0.02;
  c.cloud_max_range = 100.0;
  std::vector<float> many(10000, 5.0f);
  applyCloudRangeModel(c, rng, many.data(), static_cast<int>(many.size()));
  double sum = 0, sum2 = 0;
  for (float v : many) sum += v - 5.0, sum2 += (v - 5.0) * (v - 5.0);
  const double mean = sum / many.size(), sd = std::sqrt(sum2 / many.size() - mean * mean);
  EXPECT_NEAR(mean, 0.0, 0.002);
  EXPECT_NEAR(sd, 0.02, 0.002);
}

}  // namespace
}  // namespace tianracer_sim
