// The sensor kinds the Simulator runs (one SimSensor subclass per SensorKind id of
// sensors/sensor_registry.h), each around its ROS-free core, and the one table that makes them.
// Their outputs are plain data: ranges, images, depth, IMU and p3d readings, contact states.
#ifndef TIANRACER_SIM_SIMULATOR_SIM_SENSORS_H
#define TIANRACER_SIM_SIMULATOR_SIM_SENSORS_H

#include <atomic>
#include <cstdint>
#include <functional>
#include <memory>
#include <string>
#include <vector>

#include "tianracer_sim/common/warning.h"
#include "tianracer_sim/sensors/ray/ray_plugins.h"
#include "tianracer_sim/sensors/ray/ray_sensor.h"
#include "tianracer_sim/sensors/camera/camera_sensor.h"
#include "tianracer_sim/sensors/camera/multicamera_config.h"
#include "tianracer_sim/render/renderer.h"
#include "tianracer_sim/sensors/bumper/bumper.h"
#include "tianracer_sim/sensors/drives/drives.h"
#include "tianracer_sim/sensors/imu/imu_sensor.h"
#include "tianracer_sim/sensors/p3d/p3d.h"

namespace urdf {
class ModelInterface;
}
#include "tianracer_sim/sensors/sensor_registry.h"
#include "tianracer_sim/simulator/sim_sensor.h"

namespace tianracer_sim {

/// Everything a sensor kind needs to set a sensor up.
struct SimSensorSetup {
  const SensorSpec* spec = nullptr;
  ModelId model = kNoModel;
  std::string model_name;     // also Gazebo's default namespace of some plugins
  std::string tf_prefix;      // "" or e.g. "tianracer_02": prefixes the frames of its outputs
  std::uint64_t seed = 0;     // the simulation's seed
  int index = 0;              // sensors of this kind set up before this one
  Eigen::Vector3d gravity{0.0, 0.0, -9.8};  // the world's, m/s^2
  /// A robot's URDF (world models: null): a camera whose frameName is an optical link of it
  /// stamps its images there (sensors/camera/optical_frame.h).
  const urdf::ModelInterface* urdf = nullptr;
  WarningSink warn;
  /// Throws for a link the model does not have.
  std::function<void(const std::string& link)> check_link;
  /// The shared offscreen renderer; nullptr when there is none (reported once).
  std::function<Renderer*()> renderer;
  /// The simulation (model plugins that drive look their joints up in it); may be null.
  SensorWorld* world = nullptr;
};

/// Makes the sensor of `kind`; nullptr when it has nothing to produce (e.g. a camera without a
/// gazebo_ros plugin, as in Gazebo: the reason goes to setup.warn). Throws std::exception
/// naming the sensor on bad input.
std::unique_ptr<SimSensor> makeSimSensor(const SensorKind& kind, const SimSensorSetup& setup);

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

/// camera with gazebo_ros_camera: an image (rendered) and camera_info, at the plugin's rate.
class SimCamera : public SimSensor {
 public:
  static constexpr SensorOutputs kImage = 1, kInfo = 2;
  SimCamera(const SimSensorSetup& setup, const CameraConfig& config, Renderer& renderer);
  const CameraSensor& camera() const { return sensor_; }

  SensorOutputs update(double t, SensorWorld& world) override;
  void sample(SensorOutputs outputs, SensorWorld& world) override;
  void render(const Scene& scene, const FrameRequest& request) override;
  SensorOutputs rendered() const override { return kImage; }
  SensorOutputs counted() const override { return kImage; }
  void restart(double t) override { schedule_.restart(t); }
  /// libgazebo_ros_triggered_camera: one more frame to render (any thread). Frames go out one
  /// a step while triggers are pending; without, none.
  void trigger() { ++triggers_; }

 private:
  CameraSensor sensor_;
  Schedule schedule_;
  std::atomic<int> triggers_{0};
};

/// depth (gazebo_ros_openni_kinect, gazebo_ros_depth_camera): image, depth and cloud from one
/// render at the sensor rate; camera_info at the plugin's updateRate.
class SimDepthCamera : public SimSensor {
 public:
  static constexpr SensorOutputs kImage = 1, kDepth = 2, kCloud = 4, kInfo = 8;
  SimDepthCamera(const SimSensorSetup& setup, const DepthCameraConfig& config, Renderer& renderer);
  /// The cloud is not built by render(): DepthCameraSensor::writeCloud() writes it from the
  /// image and depth on demand (the ROS publisher straight into the message buffer).
  const DepthCameraSensor& camera() const { return sensor_; }

  SensorOutputs update(double t, SensorWorld& world) override;
  void sample(SensorOutputs outputs, SensorWorld& world) override;
  void render(const Scene& scene, const FrameRequest& request) override;
  SensorOutputs rendered() const override { return kImage | kDepth | kCloud; }
  SensorOutputs counted() const override { return kImage | kDepth | kCloud; }
  void restart(double t) override;

 private:
  DepthCameraSensor sensor_;
  Schedule schedule_, info_schedule_;
};

/// multicamera (gazebo_ros_multicamera): camera i's image is output bit i (rendered), its
/// camera_info bit 32 + i; one schedule for all.
class SimMultiCamera : public SimSensor {
 public:
  static constexpr std::size_t kMaxCameras = 32;
  static SensorOutputs image(std::size_t i) { return SensorOutputs(1) << i; }
  static SensorOutputs info(std::size_t i) { return SensorOutputs(1) << (32 + i); }
  SimMultiCamera(const SimSensorSetup& setup, MultiCameraConfig config, Renderer& renderer);
  const MultiCameraConfig& config() const { return config_; }
  std::size_t size() const { return cameras_.size(); }
  const CameraSensor& camera(std::size_t i) const { return *cameras_[i]; }

  SensorOutputs update(double t, SensorWorld& world) override;
  void sample(SensorOutputs outputs, SensorWorld& world) override;
  void render(const Scene& scene, const FrameRequest& request) override;
  SensorOutputs rendered() const override { return images_; }
  SensorOutputs counted() const override { return images_; }
  void restart(double t) override { schedule_.restart(t); }

 private:
  MultiCameraConfig config_;
  std::vector<std::unique_ptr<CameraSensor>> cameras_;
  SensorOutputs images_ = 0, all_ = 0;
  Schedule schedule_;
};

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

/// libgazebo_ros_p3d: a link's ground truth, optionally relative to another link.
class SimP3d : public SimSensor {
 public:
  static constexpr SensorOutputs kReading = 1;
  SimP3d(const SimSensorSetup& setup, P3dConfig config);
  const P3dConfig& config() const { return sensor_.config(); }
  const P3dReading& reading() const { return *reading_; }
  /// The frame the reading is in (world, or the reference link with its tf_prefix) and the
  /// link's own frame.
  const std::string& frame() const { return frame_; }
  const std::string& childFrame() const { return child_; }

  SensorOutputs update(double t, SensorWorld& world) override;
  void sample(SensorOutputs outputs, SensorWorld& world) override;
  void restart(double t) override;

 private:
  void track(double t, SensorWorld& world, const std::string& link, LinkMotion* motion);

  P3dSensor sensor_;
  std::string frame_, child_;
  LinkMotion body_, reference_;
  Schedule schedule_;
  P3dReading none_;
  const P3dReading* reading_ = &none_;
};

/// contact sensor with libgazebo_ros_bumper: the link's touching pairs in the output frame.
class SimBumper : public SimSensor {
 public:
  static constexpr SensorOutputs kStates = 1;
  SimBumper(const SimSensorSetup& setup, BumperConfig config);
  const BumperConfig& config() const { return config_; }
  /// The frame the states are in: world (or map) or a link with its tf_prefix.
  const std::string& frame() const { return frame_id_; }
  const std::vector<BumperState>& states() const { return states_; }

  SensorOutputs update(double t, SensorWorld& world) override;
  void sample(SensorOutputs outputs, SensorWorld& world) override;
  void restart(double t) override { schedule_.restart(t); }

 private:
  BumperConfig config_;
  std::string frame_link_, frame_id_;
  Schedule schedule_;
  std::vector<LinkContact> contacts_;
  std::vector<BumperState> states_;
};

/// libgazebo_ros_diff_drive, libgazebo_ros_skid_steer_drive and libgazebo_ros_planar_move
/// (sensors/drives/drives.h): at every step (update()) the command is applied to the wheel joints or
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

}  // namespace tianracer_sim

#endif  // TIANRACER_SIM_SIMULATOR_SIM_SENSORS_H
