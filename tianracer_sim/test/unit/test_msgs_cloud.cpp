// A 3D lidar scan as velodyne_gazebo_plugins' PointCloud2: fields, layout, rings, left-out points.
#include <cmath>
#include <cstring>
#include <limits>
#include <vector>

#include <gtest/gtest.h>

#include "tianracer_sim/ros/laser_msgs.h"

namespace tianracer_sim {
namespace {

TEST(VelodyneCloud, FieldsPointsAndRings) {
  RaySensorConfig c;
  c.samples = 3;
  c.vertical_samples = 2;
  c.frame_name = "velodyne";
  c.velodyne = true;
  const float nan = std::numeric_limits<float>::quiet_NaN();
  const std::vector<float> ranges = {1.0f, nan, 2.0f, 3.0f, 4.0f, nan};
  std::vector<Eigen::Vector3d> dirs(6, Eigen::Vector3d::UnitX());
  dirs[3] = Eigen::Vector3d(0, 0.6, 0.8);
  sensor_msgs::PointCloud2 msg;
  toVelodyneCloud(c, ranges, dirs, ros::Time(1.5), &msg);
  EXPECT_EQ(msg.header.frame_id, "velodyne");
  EXPECT_EQ(msg.header.stamp, ros::Time(1.5));
  ASSERT_EQ(msg.fields.size(), 5u);
  const char* names[] = {"x", "y", "z", "intensity", "ring"};
  const unsigned offsets[] = {0, 4, 8, 16, 20};
  for (int f = 0; f < 5; ++f) {
    EXPECT_EQ(msg.fields[f].name, names[f]);
    EXPECT_EQ(msg.fields[f].offset, offsets[f]);
    EXPECT_EQ(msg.fields[f].count, 1u);
  }
  EXPECT_EQ(msg.fields[4].datatype, sensor_msgs::PointField::UINT16);
  EXPECT_EQ(msg.fields[3].datatype, sensor_msgs::PointField::FLOAT32);
  EXPECT_EQ(msg.point_step, 32u);
  EXPECT_EQ(msg.height, 1u);
  EXPECT_EQ(msg.width, 4u);  // the two NaN ranges are left out
  EXPECT_EQ(msg.row_step, 4u * 32u);
  EXPECT_EQ(msg.data.size(), 4u * 32u);
  EXPECT_TRUE(msg.is_dense);
  const auto pointAt = [&](int p, float* xyz, std::uint16_t* ring) {
    std::memcpy(xyz, &msg.data[p * 32], 12);
    std::memcpy(ring, &msg.data[p * 32 + 20], 2);
  };
  float xyz[3];
  std::uint16_t ring;
  pointAt(0, xyz, &ring);
  EXPECT_FLOAT_EQ(xyz[0], 1.0f);
  EXPECT_EQ(ring, 0);
  pointAt(2, xyz, &ring);  // range 3 along (0, 0.6, 0.8), the first of ring 1
  EXPECT_FLOAT_EQ(xyz[1], 1.8f);
  EXPECT_FLOAT_EQ(xyz[2], 2.4f);
  EXPECT_EQ(ring, 1);
  // Buffers are reused: a second conversion of fewer points shrinks the message.
  const std::vector<float> fewer = {1.0f, nan, nan, nan, nan, nan};
  toVelodyneCloud(c, fewer, dirs, ros::Time(2.0), &msg);
  EXPECT_EQ(msg.width, 1u);
  EXPECT_EQ(msg.data.size(), 32u);
}

}  // namespace
}  // namespace tianracer_sim
