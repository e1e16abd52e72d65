// libhector_gazebo_ros_sonar (hector_sonar.h): GazeboRosSonar::Load's parameters and Update's
// range (hector_gazebo_plugins/src/gazebo_ros_sonar.cpp, melodic-devel).
#include "tianracer_sim/plugins/hector/hector_sonar.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include "tianracer_sim/common/text.h"
#include "tianracer_sim/model/plugin_reader.h"

namespace tianracer_sim {

HectorSonarConfig parseHectorSonarConfig(const SensorSpec& spec, const WarningSink& warn) {
  HectorSonarConfig c;
  const PluginSpec* plugin = nullptr;
  for (const PluginSpec& p : spec.plugins) {
    if (baseName(p.filename) == "libhector_gazebo_ros_sonar.so") plugin = &p;
  }
  if (!plugin)
    throw InputError(SourceLocation{spec.source, spec.line, "sensor"},
                     "sensor '" + spec.name + "': no libhector_gazebo_ros_sonar plugin");
  if (spec.type != "ray")
    throw InputError(SourceLocation{spec.source, spec.line, "sensor"},
                     "sensor '" + spec.name + "' of type '" + spec.type +
                         "': libhector_gazebo_ros_sonar needs a ray sensor (Gazebo refuses it)");
  c.ray = parseRaySensorConfig(spec, warn);
  PluginReader r(*plugin, "sensor '" + spec.name + "', plugin " + plugin->filename, warn);
  r.robotNamespace(NamespaceRule::kAsGiven, &c.robot_namespace);
  c.frame_id = r.frame("frameId", c.ray.link);
  r.text("topicName", &c.topic_name);
  readErrorModel(r, "", &c.model);
  readUpdateTimer(r, &c.timer);
  r.ignore({"alwaysOn"});
  r.finish();
  return c;
}

std::vector<SensorTopic> publishedTopics(const HectorSonarConfig& c) {
  return {{c.topic(), "sensor_msgs/Range", c.timer.rate()}};
}

RangeReading sonarReading(const HectorSonarConfig& c, const std::vector<float>& shape_ranges,
                          double dt, HectorErrorModel1* model, std::mt19937_64& rng) {
  RangeReading out;
  out.radiation = Radiation::kUltrasound;
  out.field_of_view = static_cast<float>(std::min(std::fabs(c.ray.max_angle - c.ray.min_angle),
                                                  std::fabs(c.ray.vertical_max_angle -
                                                            c.ray.vertical_min_angle)));
  out.max_range = static_cast<float>(c.ray.range_max);
  out.min_range = static_cast<float>(c.ray.range_min);
  float range = std::numeric_limits<float>::max();
  for (float r : shape_ranges) range = std::min(range, r);
  if (range < out.max_range) {
    const Eigen::Matrix<double, 1, 1> v(static_cast<double>(range));
    range = static_cast<float>(model->apply(v, dt, rng)[0]);
    range = std::min(std::max(range, out.min_range), out.max_range);
  }
  out.range = range;
  return out;
}

}  // namespace tianracer_sim
