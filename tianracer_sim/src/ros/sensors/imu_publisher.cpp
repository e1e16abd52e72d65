// IMUs: <sensor type="imu"> with libgazebo_ros_imu_sensor, and the model plugin
// libgazebo_ros_imu (with its calibration service, which always succeeds as in Gazebo).
#include <sensor_msgs/Imu.h>
#include <std_srvs/Empty.h>

#include <tianracer_control/frames.h>

#include "factories.h"
#include "tianracer_sim/ros/imu_msgs.h"
#include "tianracer_sim/sensors/imu_sensor.h"

namespace tianracer_sim {
namespace {

class ImuPublisher : public SensorPublisher {
 public:
  ImuPublisher(const SensorSetup& setup, ImuConfig config) : robot_(setup.robot) {
    config.seed = setup.seed + 301 + static_cast<std::uint64_t>(setup.index);
    config.frame_name = tianracer_control::resolveFrame(setup.tf_prefix, config.frame_name);
    setup.check_link(config.link);
    sensor_ = std::make_unique<ImuSensor>(config, setup.gravity);
    const std::string topic = config.topic();
    setup.claim_topic(topic, "robot '" + setup.robot_name + "' IMU '" + config.name + "'");
    ros::NodeHandle root = setup.root;
    pub_ = root.advertise<sensor_msgs::Imu>(topic, 10);
    if (config.model_plugin && !config.service_name.empty()) {
      const std::string service = resolveTopic(config.robot_namespace, config.service_name);
      service_ = root.advertiseService(service, &ImuPublisher::onCalibrate, this);
    }
    const double rate = config.publishRate();
    schedule_.period = rate > 0.0 ? 1.0 / rate : 0.0;
    msg_.header.frame_id = config.frame_name;
    stat_ = setup.add_stat(topic, rate);
    ROS_INFO("IMU '%s' (%s) on link %s: %g Hz on %s (frame %s)", config.name.c_str(),
             config.plugin_filename.c_str(), config.link.c_str(), rate, topic.c_str(),
             config.frame_name.c_str());
  }

  void step(double t, const ros::Time& stamp, SensorHost& host) override {
    // The motion history is kept every step: rates and accelerations are differences.
    sensor_->record(t, host.linkPose(robot_, sensor_->config().link));
    if (!schedule_.due(t)) return;
    SensorStat& stat = host.stat(stat_);
    if (pub_.getNumSubscribers() == 0) {
      sensor_->skip();
      ++stat.skipped;
      return;
    }
    toImu(sensor_->read(), stamp, &msg_);
    pub_.publish(msg_);
    ++stat.count;
    ++stat.renders;
  }

  void restart(double t) override {
    schedule_.restart(t);
    sensor_->reset();
  }

 private:
  bool onCalibrate(std_srvs::Empty::Request&, std_srvs::Empty::Response&) { return true; }

  std::size_t robot_;
  std::unique_ptr<ImuSensor> sensor_;
  ros::Publisher pub_;
  ros::ServiceServer service_;
  Schedule schedule_;
  sensor_msgs::Imu msg_;
  std::size_t stat_ = 0;
};

}  // namespace

std::unique_ptr<SensorPublisher> makeImuPublisher(const SensorSetup& setup) {
  ImuConfig config = parseImuSensorConfig(*setup.spec, setup.robot_name, setup.warn);
  if (!config.has_plugin) {
    setup.warn("robot '" + setup.robot_name + "': IMU '" + setup.spec->name +
               "' has no libgazebo_ros_imu_sensor plugin: nothing to publish, left out");
    return nullptr;
  }
  return std::make_unique<ImuPublisher>(setup, std::move(config));
}

std::unique_ptr<SensorPublisher> makeImuPluginPublisher(const SensorSetup& setup) {
  ImuConfig config = parseImuPluginConfig(*setup.spec, setup.robot_name, setup.warn);
  if (config.topic_name.empty()) return nullptr;  // Gazebo: an empty topic publishes nothing
  return std::make_unique<ImuPublisher>(setup, std::move(config));
}

}  // namespace tianracer_sim
