// ray / gpu_ray sensors with gazebo_ros_laser: the SimLidar's scans -> sensor_msgs/LaserScan.
#include <optional>

#include <sensor_msgs/LaserScan.h>
#include <sensor_msgs/PointCloud2.h>

#include "factories.h"
#include "tianracer_sim/ros/laser_msgs.h"

namespace tianracer_sim {
namespace {

/// LaserScan for a planar lidar, PointCloud2 (velodyne_gazebo_plugins) for a 3D one.
class LidarPublisher : public SensorListener {
 public:
  LidarPublisher(SimLidar& sensor, const PublisherSetup& setup) {
    const RaySensorConfig& config = sensor.config();
    const std::string topic = publishedTopics(config).front().topic;
    setup.claim_topic(topic, setup.owner() + " sensor '" + config.name + "'");
    ros::NodeHandle root = setup.root;
    if (config.velodyne) {
      pub_ = root.advertise<sensor_msgs::PointCloud2>(topic, 5);
    } else {
      pub_ = root.advertise<sensor_msgs::LaserScan>(topic, 5);
    }
    ROS_INFO("lidar '%s' on link %s: %d x %d beams, %.4g..%.4g rad, %g Hz on %s (frame %s)",
             config.name.c_str(), config.link.c_str(), config.vertical_samples, config.samples,
             config.min_angle, config.max_angle, config.update_rate, topic.c_str(),
             config.frame_name.c_str());
    sensor.stat().name = topic;
    profile_ = setup.profile;
    convert_row_ = profileRow(profile_, "sensor " + sensor.kind() + ": publish / convert");
    send_row_ = profileRow(profile_, "sensor " + sensor.kind() + ": publish / serialise and send");
  }

  SensorOutputs wanted(const SimSensor&, SensorOutputs due) override {
    return pub_.getNumSubscribers() > 0 ? due : 0;
  }

  void onOutputs(const SimSensor& s, SensorOutputs, double t) override {
    const auto& sensor = static_cast<const SimLidar&>(s);
    const RaySensorConfig& config = sensor.config();
    std::optional<StepProfile::Scope> part(std::in_place, profile_, convert_row_);
    if (config.velodyne) {
      toVelodyneCloud(config, sensor.ranges(), sensor.directions(), ros::Time(t), &cloud_);
      part.emplace(profile_, send_row_);
      pub_.publish(cloud_);
    } else {
      toLaserScan(config, sensor.ranges(), ros::Time(t), &msg_);
      part.emplace(profile_, send_row_);
      pub_.publish(msg_);
    }
  }

 private:
  ros::Publisher pub_;
  sensor_msgs::LaserScan msg_;
  sensor_msgs::PointCloud2 cloud_;
  StepProfile* profile_ = nullptr;
  int convert_row_ = -1, send_row_ = -1;
};

}  // namespace

std::unique_ptr<SensorListener> makeLidarPublisher(SimSensor& sensor, const PublisherSetup& setup) {
  return std::make_unique<LidarPublisher>(static_cast<SimLidar&>(sensor), setup);
}

}  // namespace tianracer_sim
