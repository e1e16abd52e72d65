// The ray sensors in the simulation: a lidar scan, gazebo_ros_range and gazebo_ros_block_laser,
// each around its core (ray_sensor.h, ray_plugins.h), cast with the simulation's RayCaster.
#ifndef TIANRACER_SIM_SENSORS_RAY_SIM_RAY_H
#define TIANRACER_SIM_SENSORS_RAY_SIM_RAY_H

#include <random>
#include <vector>

#include "tianracer_sim/sensors/ray/ray_plugins.h"
#include "tianracer_sim/sensors/ray/ray_sensor.h"
#include "tianracer_sim/sensors/sim_sensor.h"

namespace tianracer_sim {

/// ray / gpu_ray: a scan (ranges in beam order; a 3D lidar's rows one after the other).
class SimLidar : public SimSensor {
 public:
  static constexpr SensorOutputs kScan = 1;
  SimLidar(const SimSensorSetup& setup, RaySensorConfig config);
  const RaySensorConfig& config() const { return sensor_.config(); }
  /// The last scan's ranges; the unit ray directions in the sensor frame.
  const std::vector<float>& ranges() const { return *ranges_; }
  const std::vector<Eigen::Vector3d>& directions() const { return sensor_.directions(); }

  SensorOutputs update(double t, SensorWorld& world) override;
  void sample(SensorOutputs outputs, SensorWorld& world) override;
  void restart(double t) override { schedule_.restart(t); }

 private:
  RaySensor sensor_;
  Schedule schedule_;
  const std::vector<float>* ranges_ = &empty_;
  std::vector<float> empty_;
};

/// ray with gazebo_ros_range: the nearest of the grid's rays (sensor_msgs/Range).
class SimRange : public SimSensor {
 public:
  static constexpr SensorOutputs kRange = 1;
  SimRange(const SimSensorSetup& setup, RangeConfig config);
  const RangeConfig& config() const { return config_; }
  const RangeReading& reading() const { return reading_; }

  SensorOutputs update(double t, SensorWorld& world) override;
  void sample(SensorOutputs outputs, SensorWorld& world) override;
  void restart(double t) override { schedule_.restart(t); }

 private:
  RangeConfig config_;
  std::mt19937_64 rng_;
  Schedule schedule_;
  RayScanBuffers buffers_;
  std::vector<float> ranges_;
  RangeReading reading_;
};

/// ray with gazebo_ros_block_laser: a point cloud over the grid (sensor_msgs/PointCloud).
class SimBlockLaser : public SimSensor {
 public:
  static constexpr SensorOutputs kCloud = 1;
  SimBlockLaser(const SimSensorSetup& setup, BlockLaserConfig config);
  const BlockLaserConfig& config() const { return config_; }
  const BlockCloud& cloud() const { return cloud_; }

  SensorOutputs update(double t, SensorWorld& world) override;
  void sample(SensorOutputs outputs, SensorWorld& world) override;
  void restart(double t) override { schedule_.restart(t); }

 private:
  BlockLaserConfig config_;
  std::mt19937_64 rng_;
  Schedule schedule_;
  RayScanBuffers buffers_;
  std::vector<float> ranges_;
  BlockCloud cloud_;
};

}  // namespace tianracer_sim

#endif  // TIANRACER_SIM_SENSORS_RAY_SIM_RAY_H
