// Topic names and rates of a sensor's gazebo_ros plugin, resolved the way gazebo_ros does it.
#ifndef TIANRACER_SIM_MODEL_SENSOR_TOPICS_H
#define TIANRACER_SIM_MODEL_SENSOR_TOPICS_H

#include <string>
#include <vector>

#include "tianracer_sim/model/robot_model.h"

namespace tianracer_sim {

/// One topic a sensor plugin publishes.
struct SensorTopic {
  std::string topic;     // fully resolved, e.g. "/rrbot/camera1/image_raw"
  std::string msg_type;  // e.g. "sensor_msgs/Image"
  double rate = 0.0;     // Hz in sim time
};

/// Joins a namespace and a name as ros::names::resolve would: an absolute name is kept,
/// a relative one is appended to the namespace (which gets a leading '/'), '//' collapsed.
std::string resolveTopic(const std::string& ns, const std::string& name);

/// The topics of the sensor's known plugin (libgazebo_ros_laser, libgazebo_ros_camera,
/// libgazebo_ros_openni_kinect), with gazebo_ros's defaults for absent parameters:
///  - laser: <robotNamespace>/<topicName>, at the sensor rate;
///  - camera: <robotNamespace>/<cameraName>/{imageTopicName, cameraInfoTopicName}, at
///    updateRate (0 = the sensor rate);
///  - openni_kinect: images and cloud at the sensor rate, both camera_infos at updateRate.
/// Empty for a sensor without a known plugin.
std::vector<SensorTopic> sensorTopics(const SensorSpec& sensor);

/// A human-readable summary: the link/joint tree with masses, joint types and limits, the
/// transmissions with their interfaces, the plugins, and the sensors with topics and rates.
std::string describeRobotModel(const RobotModel& model);

}  // namespace tianracer_sim

#endif  // TIANRACER_SIM_MODEL_SENSOR_TOPICS_H
