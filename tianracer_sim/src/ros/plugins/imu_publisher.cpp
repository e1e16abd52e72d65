// IMUs: <sensor type="imu"> with libgazebo_ros_imu_sensor, and the model plugin
// libgazebo_ros_imu (with its calibration service, which always succeeds as in Gazebo).
#include <sensor_msgs/Imu.h>
#include <std_srvs/Empty.h>

#include "factories.h"
#include "tianracer_sim/ros/imu_msgs.h"
#include "topic_publisher.h"

namespace tianracer_sim {
namespace {

void toMsg(const SimImu& sensor, const ros::Time& stamp, sensor_msgs::Imu* msg) {
  toImu(sensor.reading(), stamp, msg);
}

class ImuPublisher : public TopicPublisher<SimImu, sensor_msgs::Imu> {
 public:
  ImuPublisher(SimImu& sensor, const PublisherSetup& setup)
      : TopicPublisher(sensor, setup,
                       {sensor.config().topic(), "IMU '" + sensor.config().name + "'", 10},
                       &toMsg) {
    const ImuConfig& config = sensor.config();
    if (config.model_plugin && !config.service_name.empty()) {
      const std::string service = resolveTopic(config.robot_namespace, config.service_name);
      ros::NodeHandle root = setup.root;
      service_ = root.advertiseService(service, &ImuPublisher::onCalibrate, this);
    }
    msg_.header.frame_id = config.frame_name;
    ROS_INFO("IMU '%s' (%s) on link %s: %g Hz on %s (frame %s)", config.name.c_str(),
             config.plugin_filename.c_str(), config.link.c_str(), config.publishRate(),
             config.topic().c_str(), config.frame_name.c_str());
  }

 private:
  bool onCalibrate(std_srvs::Empty::Request&, std_srvs::Empty::Response&) { return true; }

  ros::ServiceServer service_;
};

}  // namespace

std::unique_ptr<SensorListener> makeImuPublisher(SimSensor& sensor, const PublisherSetup& setup) {
  return std::make_unique<ImuPublisher>(static_cast<SimImu&>(sensor), setup);
}

TIANRACER_SENSOR_PUBLISHER(imuKind, makeImuPublisher);
TIANRACER_SENSOR_PUBLISHER(imuPluginKind, makeImuPublisher);

}  // namespace tianracer_sim
