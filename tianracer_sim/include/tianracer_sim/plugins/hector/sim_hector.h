// hector_gazebo_plugins' sensors in the simulation: the model plugins libhector_gazebo_ros_imu,
// _gps and _magnetic, and the sensor plugin libhector_gazebo_ros_sonar on a ray sensor, each
// around its core (hector_imu.h, hector_gps.h, hector_magnetic.h, hector_sonar.h) on its
// UpdateTimer's schedule.
//
// Upstream updates its models at every timer tick whether or not anyone subscribes; so do the
// IMU, GPS and magnetometer here (skip() measures too: it is cheap), so that their noise and
// drift do not depend on who listens. The sonar casts only while heard; a tick nobody hears
// leaves its drift where it is, as upstream leaves it while nothing is in range.
#ifndef TIANRACER_SIM_PLUGINS_HECTOR_SIM_HECTOR_H
#define TIANRACER_SIM_PLUGINS_HECTOR_SIM_HECTOR_H

#include <random>
#include <string>
#include <vector>

#include "tianracer_sim/plugins/hector/hector_gps.h"
#include "tianracer_sim/plugins/hector/hector_imu.h"
#include "tianracer_sim/plugins/hector/hector_magnetic.h"
#include "tianracer_sim/plugins/hector/hector_sonar.h"
#include "tianracer_sim/plugins/p3d/p3d.h"  // LinkMotion
#include "tianracer_sim/plugins/sim_sensor.h"

namespace tianracer_sim {

/// A hector model plugin's link, state and clock: the link's motion is kept every step (its
/// velocity is a pose difference where the physics gives none), the clock ticks on the timer.
class SimHectorPlugin : public SimSensor {
 public:
  SimHectorPlugin(const std::string& kind, const SimSensorSetup& setup, const std::string& name,
                  const std::string& link, const HectorUpdateTimer& timer,
                  SensorOutputs outputs);
  SensorOutputs update(double t, SensorWorld& world) override;
  void sample(SensorOutputs, SensorWorld&) override { measure(clock_.tick(t_)); }
  void skip() override { measure(clock_.tick(t_)); }
  void restart(double t) override;

 protected:
  /// An update of the core: dt since the last one; state() and gravity() are this step's.
  virtual void measure(double dt) = 0;
  virtual void resetCore() = 0;
  const LinkState& state() const { return motion_.state(); }
  const Eigen::Vector3d& gravity() const { return gravity_; }

 private:
  HectorClock clock_;
  SensorOutputs outputs_;
  LinkMotion motion_;
  double t_ = 0.0;
  Eigen::Vector3d gravity_ = Eigen::Vector3d::Zero();
};

/// libhector_gazebo_ros_imu: the IMU message and the bias message.
class SimHectorImu : public SimHectorPlugin {
 public:
  static constexpr SensorOutputs kImu = 1, kBias = 2;
  SimHectorImu(const SimSensorSetup& setup, HectorImuConfig config);
  const HectorImuConfig& config() const { return imu_.config(); }
  const std::string& frame() const { return frame_; }
  const HectorImuReading& reading() const { return imu_.reading(); }
  /// The services' changes (calibrate, set_accel_bias, set_rate_bias), between steps.
  HectorImu& core() { return imu_; }

 private:
  void measure(double dt) override { imu_.update(dt, state(), gravity()); }
  void resetCore() override { imu_.reset(); }
  HectorImu imu_;
  std::string frame_;
};

/// libhector_gazebo_ros_gps: the fix and the velocity.
class SimHectorGps : public SimHectorPlugin {
 public:
  static constexpr SensorOutputs kFix = 1, kVelocity = 2;
  SimHectorGps(const SimSensorSetup& setup, HectorGpsConfig config);
  const HectorGpsConfig& config() const { return gps_.config(); }
  const std::string& frame() const { return frame_; }
  const HectorGpsReading& reading() const { return gps_.reading(); }
  HectorGps& core() { return gps_; }

 private:
  void measure(double dt) override { gps_.update(dt, state()); }
  void resetCore() override { gps_.reset(); }
  HectorGps gps_;
  std::string frame_;
};

/// libhector_gazebo_ros_magnetic: the field in the link's frame.
class SimHectorMagnetic : public SimHectorPlugin {
 public:
  static constexpr SensorOutputs kField = 1;
  SimHectorMagnetic(const SimSensorSetup& setup, HectorMagneticConfig config);
  const HectorMagneticConfig& config() const { return magnetic_.config(); }
  const std::string& frame() const { return frame_; }
  const Eigen::Vector3d& field() const { return magnetic_.field(); }
  HectorMagnetic& core() { return magnetic_; }

 private:
  void measure(double dt) override { magnetic_.update(dt, state().X_WL.linear()); }
  void resetCore() override { magnetic_.reset(); }
  HectorMagnetic magnetic_;
  std::string frame_;
};

/// libhector_gazebo_ros_sonar on a ray sensor: the nearest of its rays.
class SimHectorSonar : public SimSensor {
 public:
  static constexpr SensorOutputs kRange = 1;
  SimHectorSonar(const SimSensorSetup& setup, HectorSonarConfig config);
  const HectorSonarConfig& config() const { return config_; }
  const RangeReading& reading() const { return reading_; }
  /// The model, for dynamic_reconfigure.
  HectorErrorModel1& model() { return config_.model; }

  SensorOutputs update(double t, SensorWorld& world) override;
  void sample(SensorOutputs outputs, SensorWorld& world) override;
  void skip() override { clock_.tick(t_); }
  void restart(double t) override;

 private:
  HectorSonarConfig config_;
  std::mt19937_64 rng_;
  HectorClock clock_;
  double t_ = 0.0;
  RayScanBuffers buffers_;
  std::vector<float> ranges_;
  RangeReading reading_;
};

struct SensorKind;
/// The kind(s) of this folder, registered beside their classes (plugins/sensor_registry.h).
const SensorKind& hectorImuKind();
const SensorKind& hectorGpsKind();
const SensorKind& hectorMagneticKind();
const SensorKind& hectorSonarKind();

}  // namespace tianracer_sim

#endif  // TIANRACER_SIM_PLUGINS_HECTOR_SIM_HECTOR_H
