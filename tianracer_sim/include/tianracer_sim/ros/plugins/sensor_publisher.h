// The node side of the sensor seam: one publisher per simulated sensor, attached to the
// Simulator's SimSensor (plugins/sim_sensor.h) as its SensorListener. It says which due
// outputs someone subscribes to and converts the outputs it is handed into messages; the
// sensor's core, schedules and counts are the Simulator's. Each publisher registers beside its
// code with TIANRACER_SENSOR_PUBLISHER(kind function, factory): naming the kind's function, a
// publisher of a kind that does not exist does not link; checkSensorPublishers(), run when the
// node starts, finds a kind that has no publisher.
#ifndef TIANRACER_SIM_ROS_PLUGINS_SENSOR_PUBLISHER_H
#define TIANRACER_SIM_ROS_PLUGINS_SENSOR_PUBLISHER_H

#include <functional>
#include <memory>
#include <string>
#include <vector>

#include <ros/ros.h>
#include <tf2_ros/static_transform_broadcaster.h>

#include "tianracer_sim/common/step_profile.h"
#include "tianracer_sim/plugins/sensor_registry.h"
#include "tianracer_sim/plugins/sim_sensor.h"

namespace tianracer_sim {

/// Everything a publisher needs to be set up.
struct PublisherSetup {
  std::string robot_name;  // the robot's or world model's name
  std::string tf_prefix;  // "" or e.g. "tianracer_02"
  ros::NodeHandle root;   // "/" on the node's callback queue
  /// Where a camera's optical frame goes: link -> "<frameName>_optical_frame".
  tf2_ros::StaticTransformBroadcaster* static_tf = nullptr;
  /// A world model's sensor: its link is on no TF tree (nothing puts a world model's links
  /// there, neither does Gazebo), so a camera's optical frame hangs from its frameName.
  bool world_model = false;
  /// "robot 'NAME'" or "model 'NAME'": who publishes, in messages.
  std::string owner() const { return (world_model ? "model '" : "robot '") + robot_name + "'"; }
  /// Throws when another sensor already publishes `topic`.
  std::function<void(const std::string& topic, const std::string& owner)> claim_topic;
  /// The step profile (null: not profiling): publishers may time the parts of their
  /// publication in rows "sensor <kind>: publish / ..." (common/step_profile.h).
  StepProfile* profile = nullptr;
};

/// Makes the publisher of `sensor` by its kind (it also names sensor.stat() after its topic).
/// Throws std::exception naming the sensor (a topic another sensor publishes).
std::unique_ptr<SensorListener> makeSensorPublisher(SimSensor& sensor, const PublisherSetup& setup);

using SensorPublisherFactory = std::unique_ptr<SensorListener> (*)(SimSensor& sensor,
                                                                   const PublisherSetup& setup);
/// Registers the publisher of a SensorKind id (TIANRACER_SENSOR_PUBLISHER); true, for the
/// static registrar.
bool registerSensorPublisher(const std::string& kind, SensorPublisherFactory factory);
/// What is wrong between `kinds` and the registered publishers, one line each: a kind without
/// a publisher, a kind with two. Empty when nothing.
std::vector<std::string> sensorPublisherProblems(const std::vector<SensorKind>& kinds);
/// Throws std::logic_error listing the problems of the registered kinds, if any (the node's
/// start).
void checkSensorPublishers();

#define TIANRACER_SENSOR_PUBLISHER_CAT2(a, b) a##b
#define TIANRACER_SENSOR_PUBLISHER_CAT(a, b) TIANRACER_SENSOR_PUBLISHER_CAT2(a, b)
/// Registers `factory` as the publisher of the kind `kind_function()` returns (the kind's
/// function, declared in its plugins/<kind>/ header) when the library loads.
#define TIANRACER_SENSOR_PUBLISHER(kind_function, factory)                                \
  static const bool TIANRACER_SENSOR_PUBLISHER_CAT(sensor_publisher_registered_, __LINE__) = \
      ::tianracer_sim::registerSensorPublisher(kind_function().id, factory)

}  // namespace tianracer_sim

#endif  // TIANRACER_SIM_ROS_PLUGINS_SENSOR_PUBLISHER_H
