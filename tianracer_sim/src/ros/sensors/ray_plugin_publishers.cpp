// ray sensors with gazebo_ros_range or gazebo_ros_block_laser: sensor_msgs/Range and
// sensor_msgs/PointCloud on <robotNamespace>/<topicName>.
#include <sensor_msgs/PointCloud.h>
#include <sensor_msgs/Range.h>

#include "factories.h"
#include "tianracer_sim/ros/laser_msgs.h"

namespace tianracer_sim {
namespace {

class RangePublisher : public SensorListener {
 public:
  RangePublisher(SimRange& sensor, const PublisherSetup& setup) {
    const RangeConfig& c = sensor.config();
    const std::string topic = publishedTopics(c).front().topic;
    setup.claim_topic(topic, setup.owner() + " range sensor '" + c.ray.name + "'");
    ros::NodeHandle root = setup.root;
    pub_ = root.advertise<sensor_msgs::Range>(topic, 1);
    ROS_INFO("range '%s' on link %s: %d x %d rays, %.4g..%.4g m, fov %.4g, %g Hz on %s (frame %s)",
             c.ray.name.c_str(), c.ray.link.c_str(), c.ray.vertical_samples, c.ray.samples,
             c.ray.range_min, c.ray.range_max, c.fov, c.publishRate(), topic.c_str(),
             c.frame_name.c_str());
    sensor.stat().name = topic;
  }
  SensorOutputs wanted(const SimSensor&, SensorOutputs due) override {
    return pub_.getNumSubscribers() > 0 ? due : 0;
  }
  void onOutputs(const SimSensor& s, SensorOutputs, double t) override {
    const auto& sensor = static_cast<const SimRange&>(s);
    toRange(sensor.config(), sensor.reading(), ros::Time(t), &msg_);
    pub_.publish(msg_);
  }

 private:
  ros::Publisher pub_;
  sensor_msgs::Range msg_;
};

class BlockLaserPublisher : public SensorListener {
 public:
  BlockLaserPublisher(SimBlockLaser& sensor, const PublisherSetup& setup) {
    const BlockLaserConfig& c = sensor.config();
    const std::string topic = publishedTopics(c).front().topic;
    setup.claim_topic(topic, setup.owner() + " block laser '" + c.ray.name + "'");
    ros::NodeHandle root = setup.root;
    pub_ = root.advertise<sensor_msgs::PointCloud>(topic, 1);
    ROS_INFO("block laser '%s' on link %s: %d x %d points, %g Hz on %s (frame %s)",
             c.ray.name.c_str(), c.ray.link.c_str(), c.rows(), c.columns(), c.ray.update_rate,
             topic.c_str(), c.frame_name.c_str());
    sensor.stat().name = topic;
  }
  SensorOutputs wanted(const SimSensor&, SensorOutputs due) override {
    return pub_.getNumSubscribers() > 0 ? due : 0;
  }
  void onOutputs(const SimSensor& s, SensorOutputs, double t) override {
    const auto& sensor = static_cast<const SimBlockLaser&>(s);
    toPointCloud(sensor.config(), sensor.cloud(), ros::Time(t), &msg_);
    pub_.publish(msg_);
  }

 private:
  ros::Publisher pub_;
  sensor_msgs::PointCloud msg_;
};

}  // namespace

std::unique_ptr<SensorListener> makeRangePublisher(SimSensor& sensor, const PublisherSetup& setup) {
  return std::make_unique<RangePublisher>(static_cast<SimRange&>(sensor), setup);
}

std::unique_ptr<SensorListener> makeBlockLaserPublisher(SimSensor& sensor,
                                                        const PublisherSetup& setup) {
  return std::make_unique<BlockLaserPublisher>(static_cast<SimBlockLaser&>(sensor), setup);
}

}  // namespace tianracer_sim
