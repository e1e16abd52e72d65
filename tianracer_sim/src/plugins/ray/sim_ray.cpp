#include "tianracer_sim/plugins/ray/sim_ray.h"

#include <tianracer_control/naming.h>

#include "tianracer_sim/plugins/sensor_registry.h"

namespace tianracer_sim {

namespace {

// An empty <robotNamespace/> on gazebo_ros_laser is the model's name (RaySensorConfig).
RaySensorConfig parseLidar(const SensorSpec& sensor, const std::string& model_name,
                           const WarningSink& warn) {
  RaySensorConfig config = parseRaySensorConfig(sensor, warn);
  if (config.namespace_from_model) config.robot_namespace = model_name;
  return config;
}

std::unique_ptr<SimSensor> makeLidar(const SimSensorSetup& setup) {
  RaySensorConfig config = parseLidar(*setup.spec, setup.model_name, setup.warn);
  config.seed = setup.seed + static_cast<std::uint64_t>(setup.index);
  config.frame_name = resolveFrame(setup.tf_prefix, config.frame_name);
  return std::make_unique<SimLidar>(setup, std::move(config));
}

std::unique_ptr<SimSensor> makeRange(const SimSensorSetup& setup) {
  RangeConfig config = parseRangeConfig(*setup.spec, setup.warn);
  config.seed = setup.seed + 501 + static_cast<std::uint64_t>(setup.index);
  config.frame_name = resolveFrame(setup.tf_prefix, config.frame_name);
  if (config.topic_name.empty()) return nullptr;  // gazebo_ros_range: no topic, nothing published
  return std::make_unique<SimRange>(setup, std::move(config));
}

std::unique_ptr<SimSensor> makeBlockLaser(const SimSensorSetup& setup) {
  BlockLaserConfig config = parseBlockLaserConfig(*setup.spec, setup.warn);
  config.seed = setup.seed + 601 + static_cast<std::uint64_t>(setup.index);
  config.frame_name = resolveFrame(setup.tf_prefix, config.frame_name);
  if (config.topic_name.empty()) return nullptr;
  return std::make_unique<SimBlockLaser>(setup, std::move(config));
}

}  // namespace

const SensorKind& lidarKind() {
  static const SensorKind kind = {"lidar", {"ray", "gpu_ray"},
       {"libgazebo_ros_laser.so", "libgazebo_ros_gpu_laser.so", "libgazebo_ros_velodyne_laser.so",
        "libgazebo_ros_velodyne_gpu_laser.so"},
       &topicsOf<parseLidar>, &makeLidar, /*type_default=*/true};
  return kind;
}
TIANRACER_SENSOR_KIND(lidarKind);

const SensorKind& rangeKind() {
  static const SensorKind kind = {"range", {"ray", "gpu_ray"}, {"libgazebo_ros_range.so"}, &topicsOf<parseRangeConfig>, &makeRange};
  return kind;
}
TIANRACER_SENSOR_KIND(rangeKind);

const SensorKind& blockLaserKind() {
  static const SensorKind kind = {"block_laser", {"ray", "gpu_ray"}, {"libgazebo_ros_block_laser.so"},
                                   &topicsOf<parseBlockLaserConfig>, &makeBlockLaser};
  return kind;
}
TIANRACER_SENSOR_KIND(blockLaserKind);

namespace {

RaySensorConfig checkedLidar(const SimSensorSetup& setup, RaySensorConfig config) {
  setup.check_link(config.link);
  return config;
}

}  // namespace

SimLidar::SimLidar(const SimSensorSetup& setup, RaySensorConfig config)
    : SimCoreSensor("lidar", setup, config.name, config.link, RaySensor(checkedLidar(setup, config)),
                    config.update_rate) {}

void SimLidar::sample(SensorOutputs, SensorWorld& world) {
  const Scene& scene = world.scene();
  setOutput(core_.scan(world.caster(), scene, world.linkPose(link())));
}

}  // namespace tianracer_sim
