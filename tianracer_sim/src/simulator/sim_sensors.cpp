#include "tianracer_sim/simulator/sim_sensors.h"

#include <map>
#include <stdexcept>

#include <tianracer_control/frames.h>

#include "tianracer_sim/sensors/camera/optical_frame.h"

namespace tianracer_sim {

namespace tc = tianracer_control;

namespace {

double periodOf(double rate) { return rate > 0.0 ? 1.0 / rate : 0.0; }

LinkRef linkOf(const SimSensorSetup& setup, const std::string& link) {
  return LinkRef{setup.model, link};
}

// --- factories, one per SensorKind id -----------------------------------------------------------

std::unique_ptr<SimSensor> makeLidar(const SimSensorSetup& setup) {
  RaySensorConfig config = parseRaySensorConfig(*setup.spec, setup.warn);
  config.seed = setup.seed + static_cast<std::uint64_t>(setup.index);
  config.frame_name = tc::resolveFrame(setup.tf_prefix, config.frame_name);
  return std::make_unique<SimLidar>(setup, std::move(config));
}

std::unique_ptr<SimSensor> makeRange(const SimSensorSetup& setup) {
  RangeConfig config = parseRangeConfig(*setup.spec, setup.warn);
  config.seed = setup.seed + 501 + static_cast<std::uint64_t>(setup.index);
  config.frame_name = tc::resolveFrame(setup.tf_prefix, config.frame_name);
  if (config.topic_name.empty()) return nullptr;  // gazebo_ros_range: no topic, nothing published
  return std::make_unique<SimRange>(setup, std::move(config));
}

std::unique_ptr<SimSensor> makeBlockLaser(const SimSensorSetup& setup) {
  BlockLaserConfig config = parseBlockLaserConfig(*setup.spec, setup.warn);
  config.seed = setup.seed + 601 + static_cast<std::uint64_t>(setup.index);
  config.frame_name = tc::resolveFrame(setup.tf_prefix, config.frame_name);
  if (config.topic_name.empty()) return nullptr;
  return std::make_unique<SimBlockLaser>(setup, std::move(config));
}

// Before the tf_prefix: the URDF's link names are the robot's own.
void useOwnOpticalFrame(const SimSensorSetup& setup, CameraConfig& camera) {
  if (setup.urdf)
    camera.frame_is_optical =
        usesOwnOpticalFrame(*setup.urdf, camera.link, camera.X_LO(), camera.frame_name);
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
  camera.frame_name = tc::resolveFrame(setup.tf_prefix, camera.frame_name);
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
    throw CameraError("robot '" + setup.model_name + "': multicamera sensor '" +
                      setup.spec->name + "' has " + std::to_string(config.cameras.size()) +
                      " cameras; at most " + std::to_string(SimMultiCamera::kMaxCameras) +
                      " are simulated");
  }
  Renderer* renderer = setup.renderer();
  if (!renderer) return nullptr;
  for (CameraConfig& c : config.cameras) {
    c.noise_seed ^= static_cast<uint32_t>(setup.seed);
    if (c.noise_seed == 0) c.noise_seed = 1;
    useOwnOpticalFrame(setup, c);
    c.frame_name = tc::resolveFrame(setup.tf_prefix, c.frame_name);
  }
  return std::make_unique<SimMultiCamera>(setup, std::move(config), *renderer);
}

std::unique_ptr<SimSensor> makeImu(const SimSensorSetup& setup) {
  ImuConfig config = parseImuSensorConfig(*setup.spec, setup.model_name, setup.warn);
  if (!config.has_plugin) {
    setup.warn("robot '" + setup.model_name + "': IMU '" + setup.spec->name +
               "' has no libgazebo_ros_imu_sensor plugin: nothing to publish, left out");
    return nullptr;
  }
  return std::make_unique<SimImu>(setup, std::move(config));
}

std::unique_ptr<SimSensor> makeImuPlugin(const SimSensorSetup& setup) {
  ImuConfig config = parseImuPluginConfig(*setup.spec, setup.model_name, setup.warn);
  if (config.topic_name.empty()) return nullptr;  // Gazebo: an empty topic publishes nothing
  return std::make_unique<SimImu>(setup, std::move(config));
}

std::unique_ptr<SimSensor> makeP3d(const SimSensorSetup& setup) {
  return std::make_unique<SimP3d>(setup, parseP3dConfig(*setup.spec, setup.model_name, setup.warn));
}

std::unique_ptr<SimSensor> makeBumper(const SimSensorSetup& setup) {
  BumperConfig config = parseBumperConfig(*setup.spec, setup.model_name, setup.warn);
  if (config.topic_name.empty()) {
    if (setup.warn) {
      setup.warn("contact sensor '" + config.name + "' of model '" + setup.model_name +
                 "' has no libgazebo_ros_bumper plugin: nothing published (as in Gazebo)");
    }
    return nullptr;
  }
  return std::make_unique<SimBumper>(setup, std::move(config));
}

std::unique_ptr<SimSensor> makeDrive(const SimSensorSetup& setup) {
  return std::make_unique<SimDrive>(setup, parseDriveConfig(*setup.spec, setup.model_name, setup.warn));
}

}  // namespace

std::unique_ptr<SimSensor> makeSimSensor(const SensorKind& kind, const SimSensorSetup& setup) {
  using Factory = std::unique_ptr<SimSensor> (*)(const SimSensorSetup&);
  static const std::map<std::string, Factory> factories = {
      {"lidar", &makeLidar},   {"camera", &makeCamera}, {"multicamera", &makeMultiCamera},
      {"depth_camera", &makeDepthCamera}, {"imu", &makeImu}, {"imu_plugin", &makeImuPlugin},
      {"p3d", &makeP3d},       {"bumper", &makeBumper},
      {"range", &makeRange},   {"block_laser", &makeBlockLaser},
      {"drive", &makeDrive},
  };
  const auto it = factories.find(kind.id);
  if (it == factories.end())
    throw std::logic_error("sensor kind '" + kind.id + "' has no simulator sensor registered");
  return it->second(setup);
}

// --- lidar ----------------------------------------------------------------------------------------

SimLidar::SimLidar(const SimSensorSetup& setup, RaySensorConfig config)
    : SimSensor("lidar", config.name, linkOf(setup, config.link), setup.model_name),
      sensor_(config) {
  setup.check_link(config.link);
  schedule_.period = periodOf(config.update_rate);
  stat().name = config.name;
  stat().target = config.update_rate;
}

SensorOutputs SimLidar::update(double t, SensorWorld&) {
  // The schedule runs whether or not anyone listens, so a new subscriber gets the rate.
  return schedule_.due(t) ? kScan : 0;
}

void SimLidar::sample(SensorOutputs, SensorWorld& world) {
  const Scene& scene = world.scene();
  ranges_ = &sensor_.scan(world.caster(), scene, world.linkPose(link()));
}

// --- range and block laser ------------------------------------------------------------------------

SimRange::SimRange(const SimSensorSetup& setup, RangeConfig config)
    : SimSensor("range", config.ray.name, linkOf(setup, config.ray.link), setup.model_name),
      config_(std::move(config)), rng_(config_.seed) {
  setup.check_link(config_.ray.link);
  schedule_.period = periodOf(config_.publishRate());
  stat().name = config_.ray.name;
  stat().target = config_.publishRate();
}

SensorOutputs SimRange::update(double t, SensorWorld&) { return schedule_.due(t) ? kRange : 0; }

void SimRange::sample(SensorOutputs, SensorWorld& world) {
  const Scene& scene = world.scene();
  shapeRanges(config_.ray, world.caster(), scene, world.linkPose(link()) * config_.ray.X_LS,
              &buffers_, &ranges_);
  reading_ = rangeReading(config_, ranges_, rng_);
}

SimBlockLaser::SimBlockLaser(const SimSensorSetup& setup, BlockLaserConfig config)
    : SimSensor("block_laser", config.ray.name, linkOf(setup, config.ray.link), setup.model_name),
      config_(std::move(config)), rng_(config_.seed) {
  setup.check_link(config_.ray.link);
  schedule_.period = periodOf(config_.ray.update_rate);
  stat().name = config_.ray.name;
  stat().target = config_.ray.update_rate;
}

SensorOutputs SimBlockLaser::update(double t, SensorWorld&) {
  return schedule_.due(t) ? kCloud : 0;
}

void SimBlockLaser::sample(SensorOutputs, SensorWorld& world) {
  const Scene& scene = world.scene();
  shapeRanges(config_.ray, world.caster(), scene, world.linkPose(link()) * config_.ray.X_LS,
              &buffers_, &ranges_);
  blockLaserCloud(config_, ranges_, rng_, &cloud_);
}

// --- camera ---------------------------------------------------------------------------------------

SimCamera::SimCamera(const SimSensorSetup& setup, const CameraConfig& config, Renderer& renderer)
    : SimSensor("camera", setup.spec->name, linkOf(setup, config.link), setup.model_name),
      sensor_(config, renderer) {
  schedule_.period = periodOf(config.publishRate());
  stat().name = config.name;
  stat().target = config.publishRate();
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

// --- depth camera ---------------------------------------------------------------------------------

SimDepthCamera::SimDepthCamera(const SimSensorSetup& setup, const DepthCameraConfig& config,
                               Renderer& renderer)
    : SimSensor("depth_camera", setup.spec->name, linkOf(setup, config.camera.link),
                setup.model_name),
      sensor_(config, renderer) {
  schedule_.period = periodOf(config.camera.update_rate);
  info_schedule_.period = periodOf(config.camera.publishRate());
  stat().name = config.camera.name;
  stat().target = config.camera.update_rate;
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

// --- multicamera ----------------------------------------------------------------------------------

SimMultiCamera::SimMultiCamera(const SimSensorSetup& setup, MultiCameraConfig config,
                               Renderer& renderer)
    : SimSensor("multicamera", setup.spec->name, linkOf(setup, config.link), setup.model_name),
      config_(std::move(config)) {
  for (std::size_t i = 0; i < config_.cameras.size(); ++i) {
    cameras_.push_back(std::make_unique<CameraSensor>(config_.cameras[i], renderer));
    images_ |= image(i);
    all_ |= image(i) | info(i);
  }
  schedule_.period = periodOf(config_.publishRate());
  stat().name = config_.name;
  stat().target = config_.publishRate();
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

// --- IMU ------------------------------------------------------------------------------------------

SimImu::SimImu(const SimSensorSetup& setup, ImuConfig config)
    : SimSensor(config.model_plugin ? "imu_plugin" : "imu", config.name,
                linkOf(setup, config.link), setup.model_name),
      sensor_((config.seed = setup.seed + 301 + static_cast<std::uint64_t>(setup.index),
               config.frame_name = tc::resolveFrame(setup.tf_prefix, config.frame_name),
               setup.check_link(config.link), config),
              setup.gravity) {
  schedule_.period = periodOf(sensor_.config().publishRate());
  stat().name = sensor_.config().name;
  stat().target = sensor_.config().publishRate();
}

SensorOutputs SimImu::update(double t, SensorWorld& world) {
  // The motion history is kept every step: rates and accelerations are differences.
  sensor_.record(t, world.linkPose(link()));
  return schedule_.due(t) ? kReading : 0;
}

void SimImu::sample(SensorOutputs, SensorWorld& world) {
  sensor_.setGravity(world.gravity());
  reading_ = &sensor_.read();
}

void SimImu::restart(double t) {
  schedule_.restart(t);
  sensor_.reset();
}

// --- p3d ------------------------------------------------------------------------------------------

SimP3d::SimP3d(const SimSensorSetup& setup, P3dConfig config)
    : SimSensor("p3d", config.name, linkOf(setup, config.link), setup.model_name),
      sensor_((config.seed = setup.seed + 401 + static_cast<std::uint64_t>(setup.index),
               setup.check_link(config.link),
               config.reference_link.empty() ? void() : setup.check_link(config.reference_link),
               config)) {
  const P3dConfig& c = sensor_.config();
  // Frames as the sim's others: tf_prefix on links, world as it is.
  frame_ = c.reference_link.empty() ? c.frame_name : tc::resolveFrame(setup.tf_prefix, c.reference_link);
  child_ = tc::resolveFrame(setup.tf_prefix, c.link);
  schedule_.period = periodOf(c.update_rate);
  stat().name = c.name;
  stat().target = c.update_rate;
}

void SimP3d::track(double t, SensorWorld& world, const std::string& link, LinkMotion* motion) {
  const LinkRef ref{this->link().model, link};
  LinkState exact;
  if (world.linkState(ref, &exact)) {
    motion->set(t, exact);
  } else {
    motion->record(t, world.linkPose(ref));
  }
}

SensorOutputs SimP3d::update(double t, SensorWorld& world) {
  // Velocities of links off the root body are pose differences: keep the history each step.
  const P3dConfig& c = sensor_.config();
  track(t, world, c.link, &body_);
  if (!c.reference_link.empty()) track(t, world, c.reference_link, &reference_);
  return schedule_.due(t) ? kReading : 0;
}

void SimP3d::sample(SensorOutputs, SensorWorld&) {
  const P3dConfig& c = sensor_.config();
  reading_ = &sensor_.measure(body_.state(), c.reference_link.empty() ? nullptr : &reference_.state());
}

void SimP3d::restart(double t) {
  schedule_.restart(t);
  body_.reset();
  reference_.reset();
}

// --- bumper ---------------------------------------------------------------------------------------

SimBumper::SimBumper(const SimSensorSetup& setup, BumperConfig config)
    : SimSensor("bumper", config.name, linkOf(setup, config.link), setup.model_name),
      config_(std::move(config)) {
  setup.check_link(config_.link);
  const bool world = config_.frame_name == "world" || config_.frame_name == "map";
  if (!world) {
    try {
      setup.check_link(config_.frame_name);
    } catch (const std::exception&) {
      throw SensorError("contact sensor '" + config_.name + "' of model '" + setup.model_name +
                        "': <frameName> '" + config_.frame_name +
                        "' is neither world nor a link of the model");
    }
    frame_link_ = config_.frame_name;
  }
  frame_id_ = world ? config_.frame_name : tc::resolveFrame(setup.tf_prefix, config_.frame_name);
  schedule_.period = periodOf(config_.update_rate);
  stat().name = config_.name;
  stat().target = config_.update_rate;
}

SensorOutputs SimBumper::update(double t, SensorWorld&) { return schedule_.due(t) ? kStates : 0; }

void SimBumper::sample(SensorOutputs, SensorWorld& world) {
  world.linkContacts(link(), &contacts_);
  const Eigen::Isometry3d X_WF = frame_link_.empty()
                                     ? Eigen::Isometry3d::Identity()
                                     : world.linkPose(LinkRef{link().model, frame_link_});
  // The impulses come from the step just taken, with the step size now in force.
  bumperStates(contacts_, X_WF, world.dt(), &states_);
}

// --- drives ---------------------------------------------------------------------------------------

SimDrive::SimDrive(const SimSensorSetup& setup, DriveConfig config)
    : SimSensor("drive", config.name, linkOf(setup, ""), setup.model_name), core_(std::move(config)) {
  const DriveConfig& c = core_.config();
  if (!setup.world) throw std::logic_error("SimDrive needs the simulation");
  const std::string what = c.filename + " plugin '" + c.name + "' of model '" +
                           setup.model_name + "'";
  static const char* kDiffTags[] = {"leftJoint", "rightJoint"};
  static const char* kSkidTags[] = {"leftFrontJoint", "rightFrontJoint", "leftRearJoint",
                                    "rightRearJoint"};
  for (std::size_t k = 0; k < c.joints.size(); ++k) {
    std::string parent, child;
    const int i = setup.world->jointIndex(setup.model, c.joints[k], &parent, &child);
    if (i < 0) {
      const char* tag = c.kind == DriveKind::kDiffDrive ? kDiffTags[k] : kSkidTags[k];
      throw SensorError(what + ": <" + tag + "> '" + c.joints[k] +
                        "' is not a movable joint of the model (Gazebo does not load the plugin)");
    }
    joints_.push_back(i);
    parent_links_.push_back(parent);
    child_links_.push_back(child);
    wheel_tf_.push_back({tc::resolveFrame(setup.tf_prefix, parent),
                         tc::resolveFrame(setup.tf_prefix, child), Eigen::Isometry3d::Identity()});
  }
  if (c.kind == DriveKind::kPlanarMove &&
      !setup.world->setModelVelocity(setup.model, Eigen::Vector3d::Zero(), Eigen::Vector3d::Zero())) {
    throw SensorError(what + ": the model is static: there is nothing to move");
  }
  omega_.assign(joints_.size(), 0.0);
  positions_.assign(joints_.size(), 0.0);
  odom_frame_ = tc::resolveFrame(setup.tf_prefix, c.odometry_frame);
  base_frame_ = tc::resolveFrame(setup.tf_prefix, c.robot_base_frame);
  stat().name = c.name;
  stat().target = c.update_rate;
}

SensorOutputs SimDrive::update(double t, SensorWorld& world) {
  const DriveConfig& c = config();
  const ModelId id = link().model;
  t_ = t;
  const LinkState model = world.modelFrameState(id);
  if (!started_) {
    // Load: the motors hold the wheels (vel 0) with fmax = the torque.
    for (int j : joints_) world.setJointVelocity(id, j, 0.0, c.wheel_torque);
    started_ = true;
  }
  if (restart_) {
    core_.restart(restart_t_, model);
    restart_ = false;
  }
  for (std::size_t k = 0; k < joints_.size(); ++k) omega_[k] = world.jointVelocity(id, joints_[k]);
  const DriveCore::Step& step = core_.update(t, model, omega_);
  if (step.set_wheels) {
    for (std::size_t k = 0; k < joints_.size(); ++k)
      world.setJointVelocity(id, joints_[k], step.wheel_omega[k], c.wheel_torque);
  }
  if (step.set_twist) world.setModelVelocity(id, step.linear_W, step.angular_W);
  if (!step.due) return 0;
  SensorOutputs due = 0;
  if (c.kind == DriveKind::kPlanarMove || c.publish_odometry) due |= kOdometry;
  if (c.publish_wheel_tf) due |= kWheelTf;
  if (c.publish_wheel_joint_state) due |= kJointState;
  return due;
}

void SimDrive::sample(SensorOutputs outputs, SensorWorld& world) {
  const ModelId id = link().model;
  if (outputs & kJointState) {
    for (std::size_t k = 0; k < joints_.size(); ++k) positions_[k] = world.jointPosition(id, joints_[k]);
  }
  if (outputs & kWheelTf) {
    for (std::size_t k = 0; k < joints_.size(); ++k) {
      wheel_tf_[k].X_PC = world.linkPose(LinkRef{id, parent_links_[k]}).inverse() *
                          world.linkPose(LinkRef{id, child_links_[k]});
    }
  }
}

void SimDrive::restart(double t) {
  // reset_simulation cleared the motors: they hold the wheels again until the first update.
  started_ = false;
  restart_ = true;
  restart_t_ = t;
}

}  // namespace tianracer_sim
