// The cameras in the simulation: camera (gazebo_ros_camera, triggered_camera), depth camera
// (openni_kinect, depth_camera) and multicamera, each around its core (camera_sensor.h); their
// frames are rendered on the frame worker (SensorWorld::requestFrame).
#ifndef TIANRACER_SIM_PLUGINS_CAMERA_SIM_CAMERA_H
#define TIANRACER_SIM_PLUGINS_CAMERA_SIM_CAMERA_H

#include <atomic>
#include <memory>
#include <vector>

#include "tianracer_sim/render/renderer.h"
#include "tianracer_sim/plugins/camera/camera_sensor.h"
#include "tianracer_sim/plugins/camera/multicamera_config.h"
#include "tianracer_sim/plugins/sim_sensor.h"

namespace tianracer_sim {

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
  void restart(double t) override { schedule_.restart(t); }

 private:
  MultiCameraConfig config_;
  std::vector<std::unique_ptr<CameraSensor>> cameras_;
  SensorOutputs images_ = 0, all_ = 0;
  Schedule schedule_;
};

struct SensorKind;
/// The kind(s) of this folder, registered beside their classes (plugins/sensor_registry.h).
const SensorKind& cameraKind();
const SensorKind& multiCameraKind();
const SensorKind& depthCameraKind();

}  // namespace tianracer_sim

#endif  // TIANRACER_SIM_PLUGINS_CAMERA_SIM_CAMERA_H
