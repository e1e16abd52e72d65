// ray / gpu_ray sensors with gazebo_ros_laser: RaySensor scans -> sensor_msgs/LaserScan.
#include <sensor_msgs/LaserScan.h>
#include <sensor_msgs/PointCloud2.h>

#include <tianracer_control/frames.h>

#include "factories.h"
#include "tianracer_sim/lidar/ray_sensor.h"
#include "tianracer_sim/ros/laser_msgs.h"

namespace tianracer_sim {
namespace {

/// LaserScan for a planar lidar, PointCloud2 (velodyne_gazebo_plugins) for a 3D one.
class LidarPublisher : public SensorPublisher {
 public:
  LidarPublisher(const SensorSetup& setup) : robot_(setup.robot), own_body_(setup.own_body) {
    RaySensorConfig config = parseRaySensorConfig(*setup.spec, setup.warn);
    config.seed = setup.seed + static_cast<std::uint64_t>(setup.index);
    config.frame_name = tianracer_control::resolveFrame(setup.tf_prefix, config.frame_name);
    sensor_ = std::make_unique<RaySensor>(config);
    setup.check_link(config.link);
    const std::string topic = publishedTopics(config).front().topic;
    setup.claim_topic(topic, "robot '" + setup.robot_name + "' sensor '" + config.name + "'");
    ros::NodeHandle root = setup.root;
    if (config.velodyne) {
      pub_ = root.advertise<sensor_msgs::PointCloud2>(topic, 5);
    } else {
      pub_ = root.advertise<sensor_msgs::LaserScan>(topic, 5);
    }
    schedule_.period = config.update_rate > 0.0 ? 1.0 / config.update_rate : 0.0;
    ROS_INFO("lidar '%s' on link %s: %d x %d beams, %.4g..%.4g rad, %g Hz on %s (frame %s)",
             config.name.c_str(), config.link.c_str(), config.vertical_samples, config.samples,
             config.min_angle, config.max_angle, config.update_rate, topic.c_str(),
             config.frame_name.c_str());
    stat_ = setup.add_stat(topic, config.update_rate);
  }

  void step(double t, const ros::Time& stamp, SensorHost& host) override {
    // The schedule runs whether or not anyone listens, so a new subscriber gets the rate.
    if (!schedule_.due(t)) return;
    SensorStat& stat = host.stat(stat_);
    if (pub_.getNumSubscribers() == 0) {
      ++stat.skipped;
      return;
    }
    const Scene& scene = host.scene();
    const RaySensorConfig& config = sensor_->config();
    const std::vector<float>& ranges =
        sensor_->scan(host.caster(), scene, host.linkPose(robot_, config.link), own_body_);
    if (config.velodyne) {
      toVelodyneCloud(config, ranges, sensor_->directions(), stamp, &cloud_);
      pub_.publish(cloud_);
    } else {
      toLaserScan(config, ranges, stamp, &msg_);
      pub_.publish(msg_);
    }
    ++stat.count;
    ++stat.renders;
  }

  void restart(double t) override { schedule_.restart(t); }

 private:
  std::size_t robot_;
  int own_body_;
  std::unique_ptr<RaySensor> sensor_;
  ros::Publisher pub_;
  Schedule schedule_;
  sensor_msgs::LaserScan msg_;
  sensor_msgs::PointCloud2 cloud_;
  std::size_t stat_ = 0;
};

}  // namespace

std::unique_ptr<SensorPublisher> makeLidarPublisher(const SensorSetup& setup) {
  return std::make_unique<LidarPublisher>(setup);
}

}  // namespace tianracer_sim
