#include "tianracer_sim/plugins/imu/sim_imu.h"

#include <tianracer_control/naming.h>

#include "tianracer_sim/plugins/sensor_registry.h"

namespace tianracer_sim {

namespace {

std::unique_ptr<SimSensor> makeImu(const SimSensorSetup& setup) {
  ImuConfig config = parseImuSensorConfig(*setup.spec, setup.model_name, setup.warn);
  if (!config.has_plugin) {
    setup.warn("robot '" + setup.model_name + "': IMU '" + setup.spec->name +
               "' has no libgazebo_ros_imu_sensor plugin: nothing to publish, left out");
    return nullptr;
  }
  return std::make_unique<SimImu>(setup, std::move(config));
}

std::unique_ptr<SimSensor> makeImuPlugin(const SimSensorSetup& setup) {
  ImuConfig config = parseImuPluginConfig(*setup.spec, setup.model_name, setup.warn);
  if (config.topic_name.empty()) return nullptr;  // Gazebo: an empty topic publishes nothing
  return std::make_unique<SimImu>(setup, std::move(config));
}

}  // namespace

const SensorKind& imuKind() {
  static const SensorKind kind = {"imu", {"imu"}, {"libgazebo_ros_imu_sensor.so"}, &topicsOf<parseImuSensorConfig>, &makeImu};
  return kind;
}
TIANRACER_SENSOR_KIND(imuKind);

const SensorKind& imuPluginKind() {
  static const SensorKind kind = {"imu_plugin", {}, {"libgazebo_ros_imu.so"}, &topicsOf<parseImuPluginConfig>, &makeImuPlugin};
  return kind;
}
TIANRACER_SENSOR_KIND(imuPluginKind);

namespace {

ImuConfig placedImu(const SimSensorSetup& setup, ImuConfig config) {
  config.seed = setup.seed + 301 + static_cast<std::uint64_t>(setup.index);
  config.frame_name = resolveFrame(setup.tf_prefix, config.frame_name);
  setup.check_link(config.link);
  return config;
}

}  // namespace

SimImu::SimImu(const SimSensorSetup& setup, ImuConfig config)
    : SimCoreSensor(config.model_plugin ? "imu_plugin" : "imu", setup, config.name, config.link,
                    ImuSensor(placedImu(setup, config), setup.gravity), config.publishRate()) {}

void SimImu::sample(SensorOutputs, SensorWorld& world) {
  core_.setGravity(world.gravity());
  setOutput(core_.read());
}

}  // namespace tianracer_sim
