// hector_gazebo_plugins' sonar, the sensor plugin libhector_gazebo_ros_sonar on a <sensor
// type="ray"> (GazeboRosSonar, src/gazebo_ros_sonar.cpp, melodic-devel). ROS-free.
//
// At each update of its own timer (default 10 Hz, whatever the sensor's <update_rate>), dt
// since the last: range = the smallest of the grid's ranges (Gazebo's LaserShape GetRange:
// cast from range min, range max where nothing is hit; ray_sensor.h shapeRanges()); when it is
// below range max, range = sensorModel(range, dt) (hector_model.h) clipped to
// [range min, range max] (no model update otherwise); sensor_msgs/Range ULTRASOUND,
// field_of_view = min(|horizontal span|, |vertical span|) (0 for a one-row grid, as upstream),
// min and max range from <range>.
// Differences: the rays are cast at the plugin's update (Gazebo reads the sensor's last scan,
// up to one sensor period older); frameId defaults to the sensor's link (upstream
// "/sonar_link").
#ifndef TIANRACER_SIM_PLUGINS_HECTOR_HECTOR_SONAR_H
#define TIANRACER_SIM_PLUGINS_HECTOR_HECTOR_SONAR_H

#include <cstdint>
#include <random>
#include <string>
#include <vector>

#include "tianracer_sim/plugins/hector/hector_model.h"
#include "tianracer_sim/plugins/ray/ray_plugins.h"  // RangeReading
#include "tianracer_sim/plugins/ray/ray_sensor.h"

namespace tianracer_sim {

struct HectorSonarConfig {
  RaySensorConfig ray;
  std::string robot_namespace;  // "" = "/"
  std::string topic_name = "sonar";
  std::string frame_id;         // <frameId>; default the link
  HectorErrorModel1 model;
  HectorUpdateTimer timer{0.1, 0.0};  // setUpdateRate(10.0) before Load
  std::uint64_t seed = 0;

  std::string topic() const { return resolveTopic(robot_namespace, topic_name); }
};

/// A <sensor type="ray"> with libhector_gazebo_ros_sonar. Throws SensorError naming the sensor,
/// element and value.
HectorSonarConfig parseHectorSonarConfig(const SensorSpec& sensor, const WarningSink& warn = {});
/// sensor_msgs/Range on topic() at the timer's rate.
std::vector<SensorTopic> publishedTopics(const HectorSonarConfig& config);

/// An update on Gazebo's shape ranges: the reading, the model advanced when in range.
RangeReading sonarReading(const HectorSonarConfig& config, const std::vector<float>& shape_ranges,
                          double dt, HectorErrorModel1* model, std::mt19937_64& rng);

}  // namespace tianracer_sim

#endif  // TIANRACER_SIM_PLUGINS_HECTOR_HECTOR_SONAR_H
