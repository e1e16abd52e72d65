// IMUs: <sensor type="imu"> with libgazebo_ros_imu_sensor, and the model plugin
// libgazebo_ros_imu (with its calibration service, which always succeeds as in Gazebo).
#include <sensor_msgs/Imu.h>
#include <std_srvs/Empty.h>

#include "factories.h"
#include "tianracer_sim/ros/imu_msgs.h"

namespace tianracer_sim {
namespace {

class ImuPublisher : public SensorListener {
 public:
  ImuPublisher(SimImu& sensor, const PublisherSetup& setup) {
    const ImuConfig& config = sensor.config();
    const std::string topic = config.topic();
    setup.claim_topic(topic, setup.owner() + " IMU '" + config.name + "'");
    ros::NodeHandle root = setup.root;
    pub_ = root.advertise<sensor_msgs::Imu>(topic, 10);
    if (config.model_plugin && !config.service_name.empty()) {
      const std::string service = resolveTopic(config.robot_namespace, config.service_name);
      service_ = root.advertiseService(service, &ImuPublisher::onCalibrate, this);
    }
    msg_.header.frame_id = config.frame_name;
    sensor.stat().name = topic;
    ROS_INFO("IMU '%s' (%s) on link %s: %g Hz on %s (frame %s)", config.name.c_str(),
             config.plugin_filename.c_str(), config.link.c_str(), config.publishRate(),
             topic.c_str(), config.frame_name.c_str());
  }

  SensorOutputs wanted(const SimSensor&, SensorOutputs due) override {
    return pub_.getNumSubscribers() > 0 ? due : 0;
  }

  void onOutputs(const SimSensor& sensor, SensorOutputs, double t) override {
    toImu(static_cast<const SimImu&>(sensor).reading(), ros::Time(t), &msg_);
    pub_.publish(msg_);
  }

 private:
  bool onCalibrate(std_srvs::Empty::Request&, std_srvs::Empty::Response&) { return true; }

  ros::Publisher pub_;
  ros::ServiceServer service_;
  sensor_msgs::Imu msg_;
};

}  // namespace

std::unique_ptr<SensorListener> makeImuPublisher(SimSensor& sensor, const PublisherSetup& setup) {
  return std::make_unique<ImuPublisher>(static_cast<SimImu&>(sensor), setup);
}

}  // namespace tianracer_sim
