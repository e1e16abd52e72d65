// The model plugins that drive a model (diff_drive, skid_steer_drive, planar_move) in the
// simulation, around their core (drives.h).
#ifndef TIANRACER_SIM_PLUGINS_DRIVES_SIM_DRIVE_H
#define TIANRACER_SIM_PLUGINS_DRIVES_SIM_DRIVE_H

#include <string>
#include <vector>

#include <Eigen/Geometry>

#include "tianracer_sim/plugins/drives/drives.h"
#include "tianracer_sim/plugins/sim_sensor.h"

namespace tianracer_sim {

/// libgazebo_ros_diff_drive, libgazebo_ros_skid_steer_drive and libgazebo_ros_planar_move
/// (plugins/drives/drives.h): at every step (update()) the command is applied to the wheel joints or
/// the model; odometry, wheel TF and joint states are its outputs at the plugin's rate.
class SimDrive : public SimSensor {
 public:
  static constexpr SensorOutputs kOdometry = 1, kWheelTf = 2, kJointState = 4;
  /// Throws SensorError naming the plugin, element and joint for a wheel joint the model does
  /// not have, and for planar_move on a model that does not move.
  SimDrive(const SimSensorSetup& setup, DriveConfig config);
  const DriveConfig& config() const { return core_.config(); }
  /// A cmd_vel; false (nothing changes) for a non-finite one.
  bool setCommand(double vx, double vy, double wz) { return core_.setCommand(vx, vy, wz, t_); }
  const DriveOdometry& odometry() const { return core_.odometry(); }
  /// Its frames with the model's tf_prefix.
  const std::string& odomFrame() const { return odom_frame_; }
  const std::string& baseFrame() const { return base_frame_; }
  struct WheelTf {
    std::string parent_frame, child_frame;
    Eigen::Isometry3d X_PC = Eigen::Isometry3d::Identity();
  };
  /// Each wheel's link in its joint's parent link (publishWheelTF), as of the last sample.
  const std::vector<WheelTf>& wheelTransforms() const { return wheel_tf_; }
  /// The wheel joints and their positions (publishWheelJointState), as of the last sample.
  const std::vector<std::string>& jointNames() const { return config().joints; }
  const std::vector<double>& jointPositions() const { return positions_; }

  SensorOutputs update(double t, SensorWorld& world) override;
  void sample(SensorOutputs outputs, SensorWorld& world) override;
  void restart(double t) override;

 private:
  DriveCore core_;
  std::vector<int> joints_;
  std::vector<std::string> parent_links_, child_links_;
  std::vector<double> omega_, positions_;
  std::vector<WheelTf> wheel_tf_;
  std::string odom_frame_, base_frame_;
  double t_ = 0.0;
  bool started_ = false;
  bool restart_ = false;
  double restart_t_ = 0.0;
};

struct SensorKind;
/// The kind(s) of this folder, registered beside their classes (plugins/sensor_registry.h).
const SensorKind& driveKind();

}  // namespace tianracer_sim

#endif  // TIANRACER_SIM_PLUGINS_DRIVES_SIM_DRIVE_H
