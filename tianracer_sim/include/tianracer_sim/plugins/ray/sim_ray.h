// The ray sensors in the simulation: a lidar scan, gazebo_ros_range and gazebo_ros_block_laser,
// each around its core (ray_sensor.h, ray_plugins.h), cast with the simulation's RayCaster.
#ifndef TIANRACER_SIM_PLUGINS_RAY_SIM_RAY_H
#define TIANRACER_SIM_PLUGINS_RAY_SIM_RAY_H

#include <random>
#include <string>
#include <vector>

#include "tianracer_sim/plugins/ray/ray_plugins.h"
#include "tianracer_sim/plugins/ray/ray_sensor.h"
#include "tianracer_sim/plugins/sim_sensor.h"

namespace tianracer_sim {

/// ray / gpu_ray: a scan (ranges in beam order; a 3D lidar's rows one after the other).
class SimLidar : public SimCoreSensor<RaySensor, std::vector<float>> {
 public:
  static constexpr SensorOutputs kScan = kOutput;
  SimLidar(const SimSensorSetup& setup, RaySensorConfig config);
  /// The last scan's ranges; the unit ray directions in the sensor frame.
  const std::vector<float>& ranges() const { return output(); }
  const std::vector<Eigen::Vector3d>& directions() const { return core_.directions(); }

  // The schedule runs whether or not anyone listens, so a new subscriber gets the rate.
  void sample(SensorOutputs outputs, SensorWorld& world) override;
};

/// The gazebo_ros plugins over a ray sensor's grid (gazebo_ros_range, gazebo_ros_block_laser):
/// at the plugin's rate the grid is cast, its ranges shaped by the ray sensor's settings, and
/// the plugin's output measured from them with its own noise stream.
template <class Config, class Output,
          void (*Measure)(const Config&, const std::vector<float>&, std::mt19937_64&, Output*)>
class SimRayGrid : public SimCoreSensor<Config, Output> {
 public:
  SimRayGrid(const std::string& kind, const SimSensorSetup& setup, const Config& config,
             double rate)
      : SimCoreSensor<Config, Output>(kind, setup, config.ray.name, config.ray.link, config, rate),
        rng_(config.seed) {
    setup.check_link(config.ray.link);
    this->setOutput(output_);
  }

  void sample(SensorOutputs, SensorWorld& world) override {
    const Config& c = this->core_;
    const Scene& scene = world.scene();
    shapeRanges(c.ray, world.caster(), scene, world.linkPose(this->link()) * c.ray.X_LS,
                &buffers_, &ranges_);
    Measure(c, ranges_, rng_, &output_);
  }

 private:
  std::mt19937_64 rng_;
  RayScanBuffers buffers_;
  std::vector<float> ranges_;
  Output output_;
};

inline void measureRange(const RangeConfig& config, const std::vector<float>& shape_ranges,
                         std::mt19937_64& rng, RangeReading* out) {
  *out = rangeReading(config, shape_ranges, rng);
}

/// ray with gazebo_ros_range: the nearest of the grid's rays (sensor_msgs/Range), at the
/// plugin's updateRate or the sensor's, whichever is lower.
class SimRange : public SimRayGrid<RangeConfig, RangeReading, &measureRange> {
 public:
  static constexpr SensorOutputs kRange = kOutput;
  SimRange(const SimSensorSetup& setup, const RangeConfig& config)
      : SimRayGrid("range", setup, config, config.publishRate()) {}
  const RangeReading& reading() const { return output(); }
};

/// ray with gazebo_ros_block_laser: a point cloud over the grid (sensor_msgs/PointCloud), at the
/// sensor's rate.
class SimBlockLaser : public SimRayGrid<BlockLaserConfig, BlockCloud, &blockLaserCloud> {
 public:
  static constexpr SensorOutputs kCloud = kOutput;
  SimBlockLaser(const SimSensorSetup& setup, const BlockLaserConfig& config)
      : SimRayGrid("block_laser", setup, config, config.ray.update_rate) {}
  const BlockCloud& cloud() const { return output(); }
};

struct SensorKind;
/// The kind(s) of this folder, registered beside their classes (plugins/sensor_registry.h).
const SensorKind& lidarKind();
const SensorKind& rangeKind();
const SensorKind& blockLaserKind();

}  // namespace tianracer_sim

#endif  // TIANRACER_SIM_PLUGINS_RAY_SIM_RAY_H
