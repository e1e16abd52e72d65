// A topic a sensor publishes, and topic names resolved the way gazebo_ros resolves them.
#ifndef TIANRACER_SIM_MODEL_SENSOR_TOPICS_H
#define TIANRACER_SIM_MODEL_SENSOR_TOPICS_H

#include <string>

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

}  // namespace tianracer_sim

#endif  // TIANRACER_SIM_MODEL_SENSOR_TOPICS_H
