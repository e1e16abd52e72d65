#include "tianracer_sim/plugins/camera/multicamera_topics.h"

#include "tianracer_sim/plugins/camera/multicamera_config.h"

namespace tianracer_sim {

std::vector<SensorTopic> multiCameraTopics(const SensorSpec& sensor, const std::string& model_name,
                                           const WarningSink& warn) {
  const MultiCameraConfig m = parseMultiCameraConfig(sensor, model_name, warn);
  std::vector<SensorTopic> out;
  if (!m.has_plugin) return out;
  for (const CameraConfig& c : m.cameras) {
    const std::string ns = resolveTopic(c.robot_namespace, c.camera_name);
    out.push_back({resolveTopic(ns, c.image_topic), "sensor_msgs/Image", c.publishRate()});
    out.push_back({resolveTopic(ns, c.camera_info_topic), "sensor_msgs/CameraInfo", c.publishRate()});
  }
  return out;
}

}  // namespace tianracer_sim
