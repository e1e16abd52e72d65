// The topics a multicamera sensor (libgazebo_ros_multicamera) publishes, for the sensor registry.
#ifndef TIANRACER_SIM_PLUGINS_CAMERA_MULTICAMERA_TOPICS_H
#define TIANRACER_SIM_PLUGINS_CAMERA_MULTICAMERA_TOPICS_H

#include <string>
#include <vector>

#include "tianracer_sim/common/warning.h"
#include "tianracer_sim/model/robot_model.h"
#include "tianracer_sim/plugins/sensor_topics.h"

namespace tianracer_sim {

/// Each camera's image and camera_info (<robotNamespace>/<cameraName><suffix>/...) at the
/// plugin's rate; none without the plugin (Gazebo renders but publishes nothing). Throws
/// CameraError as parseMultiCameraConfig does.
std::vector<SensorTopic> multiCameraTopics(const SensorSpec& sensor, const std::string& model_name,
                                           const WarningSink& warn);

}  // namespace tianracer_sim

#endif  // TIANRACER_SIM_PLUGINS_CAMERA_MULTICAMERA_TOPICS_H
