// ray / gpu_ray sensors with gazebo_ros_laser: the SimLidar's scans -> sensor_msgs/LaserScan,
// or sensor_msgs/PointCloud2 for a 3D lidar (velodyne_gazebo_plugins).
#include <sensor_msgs/LaserScan.h>
#include <sensor_msgs/PointCloud2.h>

#include "factories.h"
#include "tianracer_sim/ros/laser_msgs.h"
#include "topic_publisher.h"

namespace tianracer_sim {
namespace {

void toScan(const SimLidar& sensor, const ros::Time& stamp, sensor_msgs::LaserScan* msg) {
  toLaserScan(sensor.config(), sensor.ranges(), stamp, msg);
}

void toCloud(const SimLidar& sensor, const ros::Time& stamp, sensor_msgs::PointCloud2* msg) {
  toVelodyneCloud(sensor.config(), sensor.ranges(), sensor.directions(), stamp, msg);
}

}  // namespace

std::unique_ptr<SensorListener> makeLidarPublisher(SimSensor& s, const PublisherSetup& setup) {
  auto& sensor = static_cast<SimLidar&>(s);
  const RaySensorConfig& c = sensor.config();
  TopicSpec spec{publishedTopics(c).front().topic, "sensor '" + c.name + "'", 5};
  spec.profile_parts = true;
  std::unique_ptr<SensorListener> publisher;
  if (c.velodyne) {
    publisher = std::make_unique<TopicPublisher<SimLidar, sensor_msgs::PointCloud2>>(
        sensor, setup, spec, &toCloud);
  } else {
    publisher = std::make_unique<TopicPublisher<SimLidar, sensor_msgs::LaserScan>>(
        sensor, setup, spec, &toScan);
  }
  ROS_INFO("lidar '%s' on link %s: %d x %d beams, %.4g..%.4g rad, %g Hz on %s (frame %s)",
           c.name.c_str(), c.link.c_str(), c.vertical_samples, c.samples, c.min_angle,
           c.max_angle, c.update_rate, spec.topic.c_str(), c.frame_name.c_str());
  return publisher;
}

TIANRACER_SENSOR_PUBLISHER(lidarKind, makeLidarPublisher);

}  // namespace tianracer_sim
