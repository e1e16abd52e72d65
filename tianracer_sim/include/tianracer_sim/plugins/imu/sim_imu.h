// The IMU in the simulation: the imu sensor (libgazebo_ros_imu_sensor) and the libgazebo_ros_imu
// model plugin, around one core (imu_sensor.h).
#ifndef TIANRACER_SIM_PLUGINS_IMU_SIM_IMU_H
#define TIANRACER_SIM_PLUGINS_IMU_SIM_IMU_H

#include "tianracer_sim/plugins/imu/imu_sensor.h"
#include "tianracer_sim/plugins/sim_sensor.h"

namespace tianracer_sim {

/// imu sensor (libgazebo_ros_imu_sensor) and the libgazebo_ros_imu model plugin.
class SimImu : public SimSensor {
 public:
  static constexpr SensorOutputs kReading = 1;
  SimImu(const SimSensorSetup& setup, ImuConfig config);
  const ImuConfig& config() const { return sensor_.config(); }
  const ImuReading& reading() const { return *reading_; }

  SensorOutputs update(double t, SensorWorld& world) override;
  void sample(SensorOutputs outputs, SensorWorld& world) override;
  void skip() override { sensor_.skip(); }
  void restart(double t) override;

 private:
  ImuSensor sensor_;
  Schedule schedule_;
  ImuReading none_;
  const ImuReading* reading_ = &none_;
};

struct SensorKind;
/// The kind(s) of this folder, registered beside their classes (plugins/sensor_registry.h).
const SensorKind& imuKind();
const SensorKind& imuPluginKind();

}  // namespace tianracer_sim

#endif  // TIANRACER_SIM_PLUGINS_IMU_SIM_IMU_H
