// The IMU in the simulation: the imu sensor (libgazebo_ros_imu_sensor) and the libgazebo_ros_imu
// model plugin, around one core (imu_sensor.h).
#ifndef TIANRACER_SIM_PLUGINS_IMU_SIM_IMU_H
#define TIANRACER_SIM_PLUGINS_IMU_SIM_IMU_H

#include "tianracer_sim/plugins/imu/imu_sensor.h"
#include "tianracer_sim/plugins/sim_sensor.h"

namespace tianracer_sim {

/// imu sensor (libgazebo_ros_imu_sensor) and the libgazebo_ros_imu model plugin.
class SimImu : public SimCoreSensor<ImuSensor, ImuReading> {
 public:
  static constexpr SensorOutputs kReading = kOutput;
  SimImu(const SimSensorSetup& setup, ImuConfig config);
  const ImuReading& reading() const { return output(); }

  void sample(SensorOutputs outputs, SensorWorld& world) override;
  void skip() override { core_.skip(); }

 private:
  // The motion history is kept every step: rates and accelerations are differences.
  void track(double t, SensorWorld& world) override { core_.record(t, world.linkPose(link())); }
  void forget() override { core_.reset(); }
};

struct SensorKind;
/// The kind(s) of this folder, registered beside their classes (plugins/sensor_registry.h).
const SensorKind& imuKind();
const SensorKind& imuPluginKind();

}  // namespace tianracer_sim

#endif  // TIANRACER_SIM_PLUGINS_IMU_SIM_IMU_H
