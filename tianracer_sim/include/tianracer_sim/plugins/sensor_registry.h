// The sensor types the simulator knows, each found by Gazebo sensor type and gazebo_ros plugin
// filename. Each kind lives in its folder plugins/<kind>/ (its settings, its core, its
// SimSensor) and registers itself there, beside its class, with one TIANRACER_SENSOR_KIND line
// (as pluginlib's PLUGINLIB_EXPORT_CLASS): there is no list to keep in step. ROS-free: the
// node's publisher of a kind registers beside the publisher, naming the kind's function
// (ros/plugins/sensor_publisher.h: a publisher of a kind that does not exist does not link, and
// the node checks at start that every kind has one); model_info asks the same registry which
// topics a model's sensors publish, so the two cannot disagree.
#ifndef TIANRACER_SIM_PLUGINS_SENSOR_REGISTRY_H
#define TIANRACER_SIM_PLUGINS_SENSOR_REGISTRY_H

#include <memory>
#include <string>
#include <type_traits>
#include <vector>

#include "tianracer_sim/model/robot_model.h"
#include "tianracer_sim/plugins/sensor_topics.h"

namespace tianracer_sim {

class SimSensor;
struct SimSensorSetup;

/// One sensor type.
/// A model plugin that publishes like a sensor (libgazebo_ros_imu, libgazebo_ros_p3d) is a
/// kind with no sensor types, matched by its plugin filename on a SensorSpec of type ""
/// (modelPluginSensor()).
struct SensorKind {
  std::string id;                         // e.g. "lidar"; names its publisher in the node
  std::vector<std::string> sensor_types;  // <sensor type="..."> values; empty: a model plugin
  std::vector<std::string> plugins;       // plugin filenames (without directory)
  /// Parses the sensor as the simulator does (throws the type's error on bad input; warnings
  /// to `warn`) and lists the topics it publishes, with their rates. `model_name` is the
  /// robot's name (Gazebo's default namespace of some plugins).
  std::vector<SensorTopic> (*topics)(const SensorSpec& sensor, const std::string& model_name,
                                     const WarningSink& warn);
  /// Sets the sensor up in the simulation (plugins/sim_sensor.h); nullptr when it has nothing
  /// to produce (e.g. a camera without a gazebo_ros plugin, as in Gazebo: the reason goes to
  /// setup.warn). Throws std::exception naming the sensor on bad input.
  std::unique_ptr<SimSensor> (*make)(const SimSensorSetup& setup);
  /// Of the kinds sharing a sensor type, the one a sensor of that type with none of their
  /// plugins gets (a bare <sensor type="ray"> is a lidar). Exactly one per shared type.
  bool type_default = false;
};

/// Registers a kind (TIANRACER_SENSOR_KIND); returns true, for the static registrar.
bool registerSensorKind(const SensorKind& kind);

#define TIANRACER_SENSOR_KIND_CAT2(a, b) a##b
#define TIANRACER_SENSOR_KIND_CAT(a, b) TIANRACER_SENSOR_KIND_CAT2(a, b)
/// Registers the kind returned by `kind_function` when the library loads; one line beside the
/// kind's class, in its folder.
#define TIANRACER_SENSOR_KIND(kind_function)                                         \
  static const bool TIANRACER_SENSOR_KIND_CAT(sensor_kind_registered_, __LINE__) = \
      ::tianracer_sim::registerSensorKind(kind_function())

/// What is wrong with a set of kinds, one line each (empty when nothing): an id used twice, a
/// kind without an id, types, plugins or functions, a plugin filename of two kinds that share a
/// type, a sensor type shared by kinds of which not exactly one is its type_default.
std::vector<std::string> sensorKindProblems(const std::vector<SensorKind>& kinds);

/// A kind's topics function from its parser, `Config Parse(spec, [model_name,] warn)`, and the
/// `publishedTopics(const Config&)` of its folder: the topics are those of the settings the
/// simulator parses, so that the two cannot disagree.
template <auto Parse>
std::vector<SensorTopic> topicsOf(const SensorSpec& sensor, const std::string& model_name,
                                  const WarningSink& warn) {
  if constexpr (std::is_invocable_v<decltype(Parse), const SensorSpec&, const WarningSink&>) {
    return publishedTopics(Parse(sensor, warn));
  } else {
    return publishedTopics(Parse(sensor, model_name, warn));
  }
}

/// Every registered kind, by id. Checked the first time it is asked for: a problem
/// (sensorKindProblems) throws std::logic_error naming it, so a program whose kinds disagree
/// stops at start, not when a model happens to use one.
const std::vector<SensorKind>& sensorKinds();

/// The kind that simulates `sensor`: the one whose types hold its type and whose plugins hold
/// one of its plugins, else the type's default (the only kind of that type, or the one marked
/// type_default); for a model plugin (type ""), the model-plugin kind of its filename. nullptr
/// when none.
const SensorKind* findSensorKind(const SensorSpec& sensor);

/// The kind of sensor type `sensor_type` that registers the plugin `filename` (its directory
/// ignored), nullptr when none. A sensor's parser that several kinds share (the ray sensor's,
/// under gazebo_ros_range, gazebo_ros_block_laser and hector's sonar) leaves the plugins of
/// the other kinds to their own parsers: the registrations say which those are.
const SensorKind* findPluginKind(const std::string& sensor_type, const std::string& filename);

/// The topics the simulator publishes for `sensor` (empty for an unknown type). Throws as
/// the kind's parser does.
std::vector<SensorTopic> sensorTopics(const SensorSpec& sensor, const std::string& model_name,
                                      const WarningSink& warn = {});

/// A model plugin <gazebo><plugin> seen as a sensor (type "", its link the plugin's bodyName),
/// so that plugins that publish like sensors go through the registry.
SensorSpec modelPluginSensor(const PluginSpec& plugin);

/// A human-readable summary: the link/joint tree with masses, joint types and limits, the
/// transmissions with their interfaces, the plugins, and the sensors with topics and rates
/// (or why a sensor is left out).
std::string describeRobotModel(const RobotModel& model);

}  // namespace tianracer_sim

#endif  // TIANRACER_SIM_PLUGINS_SENSOR_REGISTRY_H
