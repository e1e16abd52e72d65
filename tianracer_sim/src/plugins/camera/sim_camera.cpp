#include "tianracer_sim/plugins/camera/sim_camera.h"

#include <string>

#include <tianracer_control/naming.h>

#include "tianracer_sim/plugins/sensor_registry.h"

#include "tianracer_sim/plugins/camera/multicamera_topics.h"
#include "tianracer_sim/plugins/camera/optical_frame.h"

namespace tianracer_sim {

namespace {

// libgazebo_ros_camera: <robotNamespace>/<cameraName>/{image, camera_info} at updateRate (0 =
// the sensor rate). Without a plugin Gazebo renders but publishes nothing.
std::vector<SensorTopic> cameraTopics(const SensorSpec& sensor, const std::string& model_name,
                                      const WarningSink& warn) {
  CameraConfig c = parseCameraConfig(sensor, warn);
  applyModelNamespace(&c, model_name);
  if (!c.has_plugin) return {};
  const std::string ns = resolveTopic(c.robot_namespace, c.camera_name);
  return {{resolveTopic(ns, c.image_topic), "sensor_msgs/Image", c.publishRate()},
          {resolveTopic(ns, c.camera_info_topic), "sensor_msgs/CameraInfo", c.publishRate()}};
}

// libgazebo_ros_openni_kinect / libgazebo_ros_depth_camera: images and cloud at the sensor
// rate, both camera_infos at the plugin's updateRate.
std::vector<SensorTopic> depthCameraTopics(const SensorSpec& sensor, const std::string& model_name,
                                           const WarningSink& warn) {
  DepthCameraConfig d = parseDepthCameraConfig(sensor, warn);
  applyModelNamespace(&d.camera, model_name);
  const CameraConfig& c = d.camera;
  if (!c.has_plugin) return {};
  const std::string ns = resolveTopic(c.robot_namespace, c.camera_name);
  return {{resolveTopic(ns, c.image_topic), "sensor_msgs/Image", c.update_rate},
          {resolveTopic(ns, d.depth_image_topic), "sensor_msgs/Image", c.update_rate},
          {resolveTopic(ns, d.point_cloud_topic), "sensor_msgs/PointCloud2", c.update_rate},
          {resolveTopic(ns, c.camera_info_topic), "sensor_msgs/CameraInfo", c.publishRate()},
          {resolveTopic(ns, d.depth_camera_info_topic), "sensor_msgs/CameraInfo",
           c.publishRate()}};
}

// Before the tf_prefix: the URDF's link names are the robot's own.
void useOwnOpticalFrame(const SimSensorSetup& setup, CameraConfig& camera) {
  camera.frame_is_optical = usesOwnOpticalFrame(setup.urdf, camera);
}

// The renderer for a camera or depth camera with its gazebo_ros plugin, its frame and noise
// seed resolved; null when it is left out (without the plugin: said; without a renderer).
Renderer* cameraRenderer(const SimSensorSetup& setup, CameraConfig& camera, uint32_t seed_offset) {
  if (!camera.has_plugin) {
    setup.warn("robot '" + setup.model_name + "': camera '" + setup.spec->name +
               "' has no gazebo_ros plugin: nothing to publish, left out");
    return nullptr;
  }
  Renderer* renderer = setup.renderer();
  if (!renderer) return nullptr;
  useOwnOpticalFrame(setup, camera);
  camera.frame_name = resolveFrame(setup.tf_prefix, camera.frame_name);
  applyModelNamespace(&camera, setup.model_name);
  if (!camera.noise_seed)
    camera.noise_seed = static_cast<uint32_t>(setup.seed + seed_offset + setup.index);
  return renderer;
}

std::unique_ptr<SimSensor> makeCamera(const SimSensorSetup& setup) {
  setup.check_link(setup.spec->link);
  // Parse first: a bad sensor is reported even when there is no renderer.
  CameraConfig camera = parseCameraConfig(*setup.spec, setup.warn);
  Renderer* renderer = cameraRenderer(setup, camera, 101);
  if (!renderer) return nullptr;
  return std::make_unique<SimCamera>(setup, camera, *renderer);
}

std::unique_ptr<SimSensor> makeDepthCamera(const SimSensorSetup& setup) {
  setup.check_link(setup.spec->link);
  DepthCameraConfig depth = parseDepthCameraConfig(*setup.spec, setup.warn);
  Renderer* renderer = cameraRenderer(setup, depth.camera, 201);
  if (!renderer) return nullptr;
  return std::make_unique<SimDepthCamera>(setup, depth, *renderer);
}

std::unique_ptr<SimSensor> makeMultiCamera(const SimSensorSetup& setup) {
  setup.check_link(setup.spec->link);
  // Parse first: a bad sensor is reported even when there is no renderer.
  MultiCameraConfig config = parseMultiCameraConfig(*setup.spec, setup.model_name, setup.warn);
  if (!config.has_plugin) {
    setup.warn("robot '" + setup.model_name + "': multicamera '" + setup.spec->name +
               "' has no gazebo_ros plugin: nothing to publish, left out");
    return nullptr;
  }
  if (config.cameras.size() > SimMultiCamera::kMaxCameras) {
    setup.fail("robot '" + setup.model_name + "': multicamera sensor '" + setup.spec->name +
               "' has " + std::to_string(config.cameras.size()) + " cameras; at most " +
               std::to_string(SimMultiCamera::kMaxCameras) + " are simulated");
  }
  Renderer* renderer = setup.renderer();
  if (!renderer) return nullptr;
  for (CameraConfig& c : config.cameras) {
    c.noise_seed ^= static_cast<uint32_t>(setup.seed);
    if (c.noise_seed == 0) c.noise_seed = 1;
    useOwnOpticalFrame(setup, c);
    c.frame_name = resolveFrame(setup.tf_prefix, c.frame_name);
  }
  return std::make_unique<SimMultiCamera>(setup, std::move(config), *renderer);
}

}  // namespace

const SensorKind& cameraKind() {
  static const SensorKind kind = {"camera", {"camera", "wideanglecamera"},
      {"libgazebo_ros_camera.so", "libgazebo_ros_triggered_camera.so"}, &cameraTopics, &makeCamera};
  return kind;
}
TIANRACER_SENSOR_KIND(cameraKind);

const SensorKind& depthCameraKind() {
  static const SensorKind kind = {"depth_camera", {"depth"},
      {"libgazebo_ros_openni_kinect.so", "libgazebo_ros_depth_camera.so"}, &depthCameraTopics,
      &makeDepthCamera};
  return kind;
}
TIANRACER_SENSOR_KIND(depthCameraKind);

const SensorKind& multiCameraKind() {
  static const SensorKind kind = {"multicamera", {"multicamera"}, {"libgazebo_ros_multicamera.so"},
                                   &multiCameraTopics, &makeMultiCamera};
  return kind;
}
TIANRACER_SENSOR_KIND(multiCameraKind);

SimCamera::SimCamera(const SimSensorSetup& setup, const CameraConfig& config, Renderer& renderer)
    : SimSensor("camera", setup.spec->name, setup.linkRef(config.link), setup.model_name),
      sensor_(config, renderer) {
  sampleAt(schedule_, config.name, config.publishRate());
}

SensorOutputs SimCamera::update(double t, SensorWorld&) {
  if (sensor_.config().triggered) {
    // Gazebo enables a triggered camera for one frame per trigger (gazebo_ros_triggered_camera
    // PreRender / OnNewFrame), subscribers or not.
    int pending = triggers_.load();
    while (pending > 0 && !triggers_.compare_exchange_weak(pending, pending - 1)) {
    }
    return pending > 0 ? kImage | kInfo : 0;
  }
  return schedule_.due(t) ? kImage | kInfo : 0;
}

void SimCamera::sample(SensorOutputs outputs, SensorWorld& world) {
  if (outputs & kImage) world.requestFrame({this, world.linkPose(link()), kImage});
}

void SimCamera::render(const Scene& scene, const FrameRequest& request) {
  sensor_.render(scene, request.X_WL);
}

SimDepthCamera::SimDepthCamera(const SimSensorSetup& setup, const DepthCameraConfig& config,
                               Renderer& renderer)
    : SimSensor("depth_camera", setup.spec->name, setup.linkRef(config.camera.link),
                setup.model_name),
      sensor_(config, renderer) {
  sampleAt(schedule_, config.camera.name, config.camera.update_rate);
  info_schedule_.period = periodOf(config.camera.publishRate());
}

SensorOutputs SimDepthCamera::update(double t, SensorWorld&) {
  SensorOutputs due = 0;
  if (schedule_.due(t)) due |= kImage | kDepth | kCloud;
  if (info_schedule_.due(t)) due |= kInfo;
  return due;
}

void SimDepthCamera::sample(SensorOutputs outputs, SensorWorld& world) {
  const SensorOutputs frame = outputs & rendered();
  if (frame) world.requestFrame({this, world.linkPose(link()), frame});
}

void SimDepthCamera::render(const Scene& scene, const FrameRequest& request) {
  // The cloud is not built here but written from image and depth by whoever wants it.
  DepthOutputs render;
  render.image = request.outputs & (kImage | kCloud);
  render.depth = request.outputs & (kDepth | kCloud);
  render.cloud = false;
  sensor_.render(scene, request.X_WL, render);
}

void SimDepthCamera::restart(double t) {
  schedule_.restart(t);
  info_schedule_.restart(t);
}

SimMultiCamera::SimMultiCamera(const SimSensorSetup& setup, MultiCameraConfig config,
                               Renderer& renderer)
    : SimSensor("multicamera", setup.spec->name, setup.linkRef(config.link), setup.model_name),
      config_(std::move(config)) {
  for (std::size_t i = 0; i < config_.cameras.size(); ++i) {
    cameras_.push_back(std::make_unique<CameraSensor>(config_.cameras[i], renderer));
    images_ |= image(i);
    all_ |= image(i) | info(i);
  }
  sampleAt(schedule_, config_.name, config_.publishRate());
}

SensorOutputs SimMultiCamera::update(double t, SensorWorld&) {
  return schedule_.due(t) ? all_ : 0;
}

void SimMultiCamera::sample(SensorOutputs outputs, SensorWorld& world) {
  const SensorOutputs frame = outputs & images_;
  if (frame) world.requestFrame({this, world.linkPose(link()), frame});
}

void SimMultiCamera::render(const Scene& scene, const FrameRequest& request) {
  for (std::size_t i = 0; i < cameras_.size(); ++i) {
    if (request.outputs & image(i)) cameras_[i]->render(scene, request.X_WL);
  }
}

}  // namespace tianracer_sim
