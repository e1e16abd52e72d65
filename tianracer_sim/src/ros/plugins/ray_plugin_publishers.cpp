// ray sensors with gazebo_ros_range or gazebo_ros_block_laser: sensor_msgs/Range and
// sensor_msgs/PointCloud on <robotNamespace>/<topicName>.
#include <sensor_msgs/PointCloud.h>
#include <sensor_msgs/Range.h>

#include "factories.h"
#include "tianracer_sim/ros/laser_msgs.h"
#include "topic_publisher.h"

namespace tianracer_sim {
namespace {

void toRangeMsg(const SimRange& sensor, const ros::Time& stamp, sensor_msgs::Range* msg) {
  toRange(sensor.config(), sensor.reading(), stamp, msg);
}

void toCloudMsg(const SimBlockLaser& sensor, const ros::Time& stamp,
                sensor_msgs::PointCloud* msg) {
  toPointCloud(sensor.config(), sensor.cloud(), stamp, msg);
}

void logRange(const SimRange& sensor, const std::string& topic) {
  const RangeConfig& c = sensor.config();
  ROS_INFO("range '%s' on link %s: %d x %d rays, %.4g..%.4g m, fov %.4g, %g Hz on %s (frame %s)",
           c.ray.name.c_str(), c.ray.link.c_str(), c.ray.vertical_samples, c.ray.samples,
           c.ray.range_min, c.ray.range_max, c.fov, c.publishRate(), topic.c_str(),
           c.frame_name.c_str());
}

void logBlockLaser(const SimBlockLaser& sensor, const std::string& topic) {
  const BlockLaserConfig& c = sensor.config();
  ROS_INFO("block laser '%s' on link %s: %d x %d points, %g Hz on %s (frame %s)",
           c.ray.name.c_str(), c.ray.link.c_str(), c.rows(), c.columns(), c.ray.update_rate,
           topic.c_str(), c.frame_name.c_str());
}

/// Both plugins publish on their one topic with a queue of 1, as upstream.
template <class Sensor, class Msg>
std::unique_ptr<SensorListener> makeRayPluginPublisher(
    SimSensor& s, const PublisherSetup& setup, const std::string& label,
    void (*convert)(const Sensor&, const ros::Time&, Msg*),
    void (*log)(const Sensor&, const std::string& topic)) {
  auto& sensor = static_cast<Sensor&>(s);
  const std::string topic = publishedTopics(sensor.config()).front().topic;
  auto publisher = std::make_unique<TopicPublisher<Sensor, Msg>>(
      sensor, setup, TopicSpec{topic, label + " '" + sensor.config().ray.name + "'", 1}, convert);
  log(sensor, topic);
  return publisher;
}

}  // namespace

std::unique_ptr<SensorListener> makeRangePublisher(SimSensor& sensor, const PublisherSetup& setup) {
  return makeRayPluginPublisher(sensor, setup, "range sensor", &toRangeMsg, &logRange);
}

std::unique_ptr<SensorListener> makeBlockLaserPublisher(SimSensor& sensor,
                                                        const PublisherSetup& setup) {
  return makeRayPluginPublisher(sensor, setup, "block laser", &toCloudMsg, &logBlockLaser);
}

TIANRACER_SENSOR_PUBLISHER(rangeKind, makeRangePublisher);
TIANRACER_SENSOR_PUBLISHER(blockLaserKind, makeBlockLaserPublisher);

}  // namespace tianracer_sim
