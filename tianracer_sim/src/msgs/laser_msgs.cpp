#include "tianracer_sim/ros/laser_msgs.h"

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

}  // namespace tianracer_sim
