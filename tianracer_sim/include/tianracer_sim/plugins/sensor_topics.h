// A topic a sensor publishes (what model_info lists and the node advertises). Topic and frame
// names are resolved by the one naming module, tianracer_control/naming.h.
#ifndef TIANRACER_SIM_PLUGINS_SENSOR_TOPICS_H
#define TIANRACER_SIM_PLUGINS_SENSOR_TOPICS_H

#include <string>

#include <tianracer_control/naming.h>

namespace tianracer_sim {

/// One topic a sensor plugin publishes.
struct SensorTopic {
  std::string topic;     // fully resolved, e.g. "/rrbot/camera1/image_raw"
  std::string msg_type;  // e.g. "sensor_msgs/Image"
  double rate = 0.0;     // Hz in sim time
};

using tianracer_control::resolveFrame;
using tianracer_control::resolveTopic;

}  // namespace tianracer_sim

#endif  // TIANRACER_SIM_PLUGINS_SENSOR_TOPICS_H
