// toLaserScan: every field gazebo_ros_laser fills, for the seed's hokuyo.
#include <cmath>
#include <limits>
#include <vector>

#include <gtest/gtest.h>

#include "tianracer_sim/ros/laser_msgs.h"

#include "lidar_test_support.h"

namespace tianracer_sim {
namespace {

using test::seedHokuyo;

TEST(LaserMsgs, SeedHokuyoFields) {
  const RaySensorConfig c = seedHokuyo();
  std::vector<float> ranges(1081, 1.5f);
  ranges[0] = std::numeric_limits<float>::infinity();
  ranges[1] = -std::numeric_limits<float>::infinity();
  const sensor_msgs::LaserScan m = toLaserScan(c, ranges, ros::Time(12, 500000000));
  EXPECT_EQ(m.header.frame_id, "lidar");
  EXPECT_EQ(m.header.stamp, ros::Time(12, 500000000));
  EXPECT_FLOAT_EQ(m.angle_min, -2.3561944902f);
  EXPECT_FLOAT_EQ(m.angle_max, 2.3561944902f);
  EXPECT_NEAR(m.angle_increment, 0.0043633, 1e-7);
  EXPECT_FLOAT_EQ(m.angle_increment, static_cast<float>(2 * 2.3561944902 / 1080));
  EXPECT_EQ(m.time_increment, 0.0f);
  EXPECT_FLOAT_EQ(m.scan_time, 0.025f);
  EXPECT_FLOAT_EQ(m.range_min, 0.1f);
  EXPECT_FLOAT_EQ(m.range_max, 10.0f);
  ASSERT_EQ(m.ranges.size(), 1081u);
  EXPECT_EQ(m.ranges[0], std::numeric_limits<float>::infinity());
  EXPECT_EQ(m.ranges[1], -std::numeric_limits<float>::infinity());
  EXPECT_EQ(m.ranges[2], 1.5f);
  EXPECT_TRUE(m.intensities.empty());
  // angle_min + (n - 1) * increment lands on angle_max.
  EXPECT_NEAR(m.angle_min + 1080 * double(m.angle_increment), m.angle_max, 1e-5);
}

TEST(LaserMsgs, ZeroRateAndReuse) {
  RaySensorConfig c = seedHokuyo();
  c.update_rate = 0;
  c.samples = 3;
  c.frame_name = "tianracer_02/lidar";
  sensor_msgs::LaserScan m;
  m.intensities.assign(5, 1.0f);
  toLaserScan(c, {1.0f, 2.0f, 3.0f}, ros::Time(1), &m);
  EXPECT_EQ(m.scan_time, 0.0f);
  EXPECT_EQ(m.header.frame_id, "tianracer_02/lidar");
  EXPECT_EQ(m.ranges, (std::vector<float>{1.0f, 2.0f, 3.0f}));
  EXPECT_TRUE(m.intensities.empty());
}

}  // namespace
}  // namespace tianracer_sim

int main(int argc, char** argv) {
  ::testing::InitGoogleTest(&argc, argv);
  return RUN_ALL_TESTS();
}
