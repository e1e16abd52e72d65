// RaySensor scans -> sensor_msgs/LaserScan, field for field as gazebo_ros_laser fills them
// (docs/model_and_sensors.md), except scan_time, which we set to the scan period.
#ifndef TIANRACER_SIM_ROS_LASER_MSGS_H
#define TIANRACER_SIM_ROS_LASER_MSGS_H

#include <vector>

#include <ros/time.h>
#include <sensor_msgs/LaserScan.h>
#include <sensor_msgs/PointCloud.h>
#include <sensor_msgs/PointCloud2.h>
#include <sensor_msgs/Range.h>

#include "tianracer_sim/plugins/ray/ray_plugins.h"
#include "tianracer_sim/plugins/ray/ray_sensor.h"

namespace tianracer_sim {

/// header.stamp = stamp, header.frame_id = frame_name; angle_min/max = min/max_angle;
/// angle_increment = (max - min) / (samples - 1); time_increment = 0 (Gazebo);
/// scan_time = 1 / update_rate (0 when the rate is 0); range_min/max from <range>;
/// ranges as given (+-inf outside the limits, REP 117); no intensities.
sensor_msgs::LaserScan toLaserScan(const RaySensorConfig& config, const std::vector<float>& ranges,
                                   const ros::Time& stamp);

/// As above into an existing message, reusing its buffers (no allocation once warm).
void toLaserScan(const RaySensorConfig& config, const std::vector<float>& ranges,
                 const ros::Time& stamp, sensor_msgs::LaserScan* msg);

/// A 3D lidar scan -> sensor_msgs/PointCloud2 as velodyne_gazebo_plugins fills it: one point
/// per finite range (NaN ranges are left out), x y z = r * direction (sensor frame), fields
/// x, y, z (FLOAT32 at 0, 4, 8), intensity (FLOAT32 at 16, 0 here), ring (UINT16 at 20),
/// point_step 32, height 1, is_dense. `directions` are RaySensor::directions(): range k is ring
/// k / samples. Reuses the message's buffers (no allocation once warm).
void toVelodyneCloud(const RaySensorConfig& config, const std::vector<float>& ranges,
                     const std::vector<Eigen::Vector3d>& directions, const ros::Time& stamp,
                     sensor_msgs::PointCloud2* msg);

/// gazebo_ros_range's message: frame_id = frameName, the reading's fields.
void toRange(const RangeConfig& config, const RangeReading& reading, const ros::Time& stamp,
             sensor_msgs::Range* msg);

/// gazebo_ros_block_laser's message: frame_id = frameName, points row by row, one channel
/// (named "", as upstream) of intensities. Reuses the message's buffers.
void toPointCloud(const BlockLaserConfig& config, const BlockCloud& cloud, const ros::Time& stamp,
                  sensor_msgs::PointCloud* msg);

}  // namespace tianracer_sim

#endif  // TIANRACER_SIM_ROS_LASER_MSGS_H
