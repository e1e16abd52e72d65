#include "tianracer_sim/ros/laser_msgs.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstring>

#include <cassert>

namespace tianracer_sim {

void toLaserScan(const RaySensorConfig& config, const std::vector<float>& ranges,
                 const ros::Time& stamp, sensor_msgs::LaserScan* msg) {
  assert(static_cast<int>(ranges.size()) == config.samples);
  msg->header.stamp = stamp;
  msg->header.frame_id = config.frame_name;
  msg->angle_min = static_cast<float>(config.min_angle);
  msg->angle_max = static_cast<float>(config.max_angle);
  msg->angle_increment = static_cast<float>(config.angleIncrement());
  msg->time_increment = 0.0f;
  msg->scan_time = config.update_rate > 0.0 ? static_cast<float>(1.0 / config.update_rate) : 0.0f;
  msg->range_min = static_cast<float>(config.range_min);
  msg->range_max = static_cast<float>(config.range_max);
  msg->ranges.assign(ranges.begin(), ranges.end());
  msg->intensities.clear();
}

sensor_msgs::LaserScan toLaserScan(const RaySensorConfig& config, const std::vector<float>& ranges,
                                   const ros::Time& stamp) {
  sensor_msgs::LaserScan msg;
  toLaserScan(config, ranges, stamp, &msg);
  return msg;
}

void toVelodyneCloud(const RaySensorConfig& config, const std::vector<float>& ranges,
                     const std::vector<Eigen::Vector3d>& directions, const ros::Time& stamp,
                     sensor_msgs::PointCloud2* msg) {
  constexpr std::uint32_t kPointStep = 32;
  msg->header.stamp = stamp;
  msg->header.frame_id = config.frame_name;
  if (msg->fields.size() != 5) {
    msg->fields.resize(5);
    const char* names[] = {"x", "y", "z", "intensity", "ring"};
    const std::uint32_t offsets[] = {0, 4, 8, 16, 20};
    for (int f = 0; f < 5; ++f) {
      msg->fields[f].name = names[f];
      msg->fields[f].offset = offsets[f];
      msg->fields[f].datatype =
          f == 4 ? sensor_msgs::PointField::UINT16 : sensor_msgs::PointField::FLOAT32;
      msg->fields[f].count = 1;
    }
  }
  const std::size_t n = std::min(ranges.size(), directions.size());
  const int samples = std::max(1, config.samples);
  msg->data.resize(n * kPointStep);
  std::uint8_t* out = msg->data.data();
  for (std::size_t k = 0; k < n; ++k) {
    const float r = ranges[k];
    if (!std::isfinite(r)) continue;
    const Eigen::Vector3d& d = directions[k];
    const float xyz[3] = {static_cast<float>(r * d.x()), static_cast<float>(r * d.y()),
                          static_cast<float>(r * d.z())};
    const float intensity = 0.0f;
    const std::uint16_t ring = static_cast<std::uint16_t>(k / samples);
    std::memset(out, 0, kPointStep);
    std::memcpy(out, xyz, sizeof(xyz));
    std::memcpy(out + 16, &intensity, sizeof(intensity));
    std::memcpy(out + 20, &ring, sizeof(ring));
    out += kPointStep;
  }
  const std::uint32_t points = static_cast<std::uint32_t>((out - msg->data.data()) / kPointStep);
  msg->data.resize(points * kPointStep);
  msg->height = 1;
  msg->width = points;
  msg->point_step = kPointStep;
  msg->row_step = points * kPointStep;
  msg->is_bigendian = false;
  msg->is_dense = true;
}

void toRange(const RangeConfig& config, const RangeReading& reading, const ros::Time& stamp,
             sensor_msgs::Range* msg) {
  msg->header.stamp = stamp;
  msg->header.frame_id = config.frame_name;
  msg->radiation_type = static_cast<std::uint8_t>(reading.radiation);
  msg->field_of_view = reading.field_of_view;
  msg->min_range = reading.min_range;
  msg->max_range = reading.max_range;
  msg->range = reading.range;
}

void toPointCloud(const BlockLaserConfig& config, const BlockCloud& cloud, const ros::Time& stamp,
                  sensor_msgs::PointCloud* msg) {
  msg->header.stamp = stamp;
  msg->header.frame_id = config.frame_name;
  const std::size_t n = cloud.intensity.size();
  msg->points.resize(n);
  for (std::size_t i = 0; i < n; ++i) {
    msg->points[i].x = cloud.xyz[3 * i];
    msg->points[i].y = cloud.xyz[3 * i + 1];
    msg->points[i].z = cloud.xyz[3 * i + 2];
  }
  msg->channels.resize(1);
  msg->channels[0].name.clear();
  msg->channels[0].values.assign(cloud.intensity.begin(), cloud.intensity.end());
}

}  // namespace tianracer_sim
