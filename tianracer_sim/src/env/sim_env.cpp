#include "tianracer_sim/env/sim_env.h"

#include <time.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstring>
#include <fstream>
#include <set>
#include <sstream>

#include <tianracer_assets/paths.h>

#include "tianracer_sim/common/text.h"
#include "tianracer_sim/plugins/camera/sim_camera.h"
#include "tianracer_sim/simulator/robot_setup.h"
#include "tianracer_sim/plugins/imu/sim_imu.h"
#include "tianracer_sim/plugins/p3d/sim_p3d.h"
#include "tianracer_sim/plugins/ray/sim_ray.h"

namespace tianracer_sim {

namespace tc = tianracer_control;

namespace {

double threadCpu() {
  timespec ts;
  clock_gettime(CLOCK_THREAD_CPUTIME_ID, &ts);
  return ts.tv_sec + 1e-9 * ts.tv_nsec;
}

std::string dirName(const std::string& path) {
  const auto slash = path.find_last_of('/');
  return slash == std::string::npos ? std::string(".") : path.substr(0, slash);
}

std::string join(const std::vector<std::string>& items) {
  std::string out;
  for (const std::string& s : items) out += (out.empty() ? "" : ", ") + s;
  return out.empty() ? "none" : out;
}

/// What a controller's command means, from its type ("<package>/Joint<What>Controller").
std::string commandKind(const std::string& type) {
  const std::string cls = type.substr(type.find('/') + 1);
  if (cls.find("Position") != std::string::npos) return "position";
  if (cls.find("Velocity") != std::string::npos) return "velocity";
  return "effort";
}

}  // namespace

std::size_t Observation::bytes() const {
  std::size_t n = itemsize;
  for (std::size_t d : shape) n *= d;
  return n;
}

// Wants the observed outputs of one sensor (nothing of the others) and notes when each was
// sampled. onOutputs runs on the frame worker for rendered outputs: read after waitFrames().
class SimEnv::Listener : public SensorListener {
 public:
  Listener(SimEnv* env, SensorOutputs want) : env_(env), want_(want) {}
  SensorOutputs wanted(const SimSensor&, SensorOutputs due) override { return due & want_; }
  void onOutputs(const SimSensor& sensor, SensorOutputs outputs, double t) override {
    for (Observation& o : env_->observations_) {
      if (o.sensor == &sensor && (o.outputs & outputs)) o.stamp = t;
    }
  }

 private:
  SimEnv* env_;
  SensorOutputs want_;
};

SimEnv::SimEnv(EnvConfig config) : config_(std::move(config)) {
  if (!config_.find_package) throw EnvError("EnvConfig: find_package is required");
  tc::WarningSink warn = config_.warn;

  // The model, as the node loads it.
  LoadOptions load;
  load.resolver.find_package = config_.find_package;
  load.warn = warn;
  std::string source;
  if (!config_.urdf.empty()) {
    if (!config_.model.empty()) throw EnvError("give either a model file or URDF text, not both");
    if (!config_.model_args.empty()) throw EnvError("model_args are xacro arguments: they need a .xacro model file");
    urdf_ = config_.urdf;
    source = "URDF text";
    load.resolver.base_dir = config_.model_dir;
  } else {
    if (config_.model.empty()) throw EnvError("no model: give a xacro/URDF file or URDF text");
    if (endsWith(config_.model, ".xacro")) {
      urdf_ = expandXacro(config_.model, config_.model_args, warn);
    } else {
      if (!config_.model_args.empty()) {
        throw EnvError("model_args are xacro arguments, but " + config_.model + " is not a .xacro file");
      }
      std::ifstream in(config_.model);
      if (!in) throw EnvError("model file " + config_.model + " cannot be read");
      std::stringstream text;
      text << in.rdbuf();
      urdf_ = text.str();
    }
    source = config_.model;
    load.resolver.base_dir = dirName(config_.model);
  }
  model_ = loadRobotModel(urdf_, source, load);
  // Its name and controllers: the one robot set-up (the node's too), on the YAML as `rosparam
  // load` puts it on the parameter server.
  if (config_.control_config.empty() && !config_.controllers.empty()) {
    throw EnvError("controllers " + join(config_.controllers) + " asked for, but no control_config");
  }
  RobotSetupRequest request;
  request.robot_name = config_.robot_name;
  if (!config_.control_namespace.empty()) request.control_namespace = config_.control_namespace;
  if (!config_.controllers.empty()) request.controllers = config_.controllers;
  request.control_config = config_.control_config;
  const RobotSetup setup = setUpRobot(model_, request, YamlControlParams(config_.control_config));
  if (warn) {
    for (const std::string& w : setup.warnings) warn(w);
  }
  robot_name_ = setup.name;
  setup_ns_ = setup.ns;
  control_ns_ = setup.control_ns;
  controller_specs_ = setup.controllers;

  // The world.
  std::string worlds_dir = config_.worlds_dir;
  if (worlds_dir.empty()) {
    const std::string pkg = config_.find_package("tianracer_sim");
    if (!pkg.empty()) worlds_dir = pkg + "/worlds";
  }
  WorldLoadOptions world_options;
  world_options.warn = warn;
  world_options.find_package = config_.find_package;
  world_ = loadWorldFile(resolveWorld(config_.world, worlds_dir), world_options);

  build(config_.seed);
  senseInitial();  // as the node's data at its start
}

SimEnv::~SimEnv() = default;

void SimEnv::build(std::uint64_t seed) {
  SimulatorOptions options;
  options.max_step_size = config_.max_step_size;
  options.seed = seed;
  options.log.warn = config_.warn;
  options.log.error = config_.warn;
  options.log.frame_error = config_.warn;
  observations_.clear();
  sim_.reset();  // the old one's frame worker ends before the new one starts
  sim_ = std::make_unique<Simulator>(world_, options);

  RobotSpawn spawn;
  spawn.name = robot_name_;
  spawn.model = model_;
  spawn.X_WB = config_.X_WB;
  spawn.drop_to_ground = config_.drop_to_ground;
  spawn.controllers = controller_specs_;
  spawn.disabled_sensors = config_.disabled_sensors;
  robot_ = sim_->addRobot(std::move(spawn));

  // What to compute: observations first (their sensors), then one listener per sensor.
  std::set<std::string> keys;
  for (const std::string& what : config_.observe) {
    if (!keys.insert(what).second) throw EnvError("observation '" + what + "' is named twice");
    observations_.push_back(resolve(what));
  }
  for (const auto& s : sim_->sensors()) {
    if (s->link().model != robot_) continue;
    SensorOutputs want = 0;
    for (const Observation& o : observations_) {
      if (o.sensor == s.get()) want |= o.outputs;
    }
    s->setListener(std::make_unique<Listener>(this, want));
  }

  // Raw commands: every controller with one, in the robot's order.
  commands_.clear();
  std::vector<std::pair<std::string, std::string>> commanded;
  const SimRobot& robot = *sim_->robot(robot_);
  for (const auto& c : robot.controllers.controllers()) {
    if (!c->hasCommand() || !c->joint()) continue;
    const tc::JointHandle& j = *c->joint();
    CommandSpec spec;
    spec.controller = c->name();
    spec.joint = j.name;
    spec.type = commandKind(c->type());
    const double inf = std::numeric_limits<double>::infinity();
    if (spec.type == "position") {
      spec.lower = j.has_position_limits ? j.lower : -inf;
      spec.upper = j.has_position_limits ? j.upper : inf;
    } else {
      const double limit = spec.type == "velocity" ? j.velocity_limit : j.effort_limit;
      spec.lower = limit > 0.0 ? -limit : -inf;
      spec.upper = limit > 0.0 ? limit : inf;
    }
    commands_.push_back(spec);
    commanded.emplace_back(spec.controller, spec.joint);
  }
  if (!drive_ && drive_problem_.empty()) {
    try {
      drive_ = std::make_unique<AckermannDrive>(
          urdf_, commanded,
          [this](const std::string& uri) {
            // The one resolver of model files (tianracer_assets); "" when it cannot say.
            tianracer_assets::UriResolver resolver;
            resolver.find_package = config_.find_package;
            resolver.base_dir = config_.urdf.empty() ? dirName(config_.model) : config_.model_dir;
            try {
              return resolver.resolve(uri);
            } catch (const tianracer_assets::ResourceError&) {
              return std::string();
            }
          },
          tc::CmdVelLimits(), config_.warn);
    } catch (const std::exception& e) {
      drive_problem_ = e.what();
    }
  }
  if (drive_) drive_->reset();
  initial_ = false;
}

std::vector<std::pair<std::string, std::string>> SimEnv::controllers() const {
  std::vector<std::pair<std::string, std::string>> out;
  for (const auto& c : sim_->robot(robot_)->controllers.controllers()) {
    out.emplace_back(c->name(), c->type());
  }
  return out;
}

void SimEnv::senseInitial() {
  sim_->sense();
  sim_->waitFrames();
  stampState();
  initial_ = true;
}

Observation SimEnv::resolve(const std::string& what) const {
  Observation o;
  o.key = what;
  if (what == "odom") {
    o.kind = Observation::Kind::kOdom;
    o.shape = {13};
    return o;
  }
  if (what == "joints") {
    JointStates js;
    sim_->jointStates(robot_, &js);
    o.kind = Observation::Kind::kJoints;
    o.shape = {3, js.name.size()};
    return o;
  }
  // A kind alias, a sensor name, or sensor/output.
  static const std::vector<std::pair<std::string, std::vector<std::string>>> aliases = {
      {"scan", {"lidar"}},
      {"image", {"camera"}},
      {"depth", {"depth_camera"}},
      {"imu", {"imu", "imu_plugin"}},
      {"ground_truth", {"p3d"}}};
  std::string name = what, output;
  const SimSensor* sensor = nullptr;
  for (const auto& [alias, kinds] : aliases) {
    if (what != alias) continue;
    std::vector<const SimSensor*> found;
    for (const auto& s : sim_->sensors()) {
      if (s->link().model == robot_ &&
          std::find(kinds.begin(), kinds.end(), s->kind()) != kinds.end()) {
        found.push_back(s.get());
      }
    }
    if (found.size() != 1) {
      std::vector<std::string> names;
      for (const SimSensor* s : found) names.push_back(s->name());
      throw EnvError("observation '" + what + "': the model has " +
                     (found.empty() ? std::string("no such sensor")
                                    : "several (" + join(names) + "): name one") +
                     " (its sensors: " + [&] {
                       std::vector<std::string> all;
                       for (const auto& [n, k] : sensors()) all.push_back(n + " (" + k + ")");
                       return join(all);
                     }() + ")");
    }
    sensor = found.front();
  }
  if (!sensor) {
    const auto slash = what.find('/');
    if (slash != std::string::npos) {
      name = what.substr(0, slash);
      output = what.substr(slash + 1);
    }
    sensor = sim_->findSensor(robot_, name);
    if (!sensor) {
      std::vector<std::string> all;
      for (const auto& [n, k] : sensors()) all.push_back(n + " (" + k + ")");
      const auto left = sim_->leftOut(robot_).find(name);
      throw EnvError("observation '" + what + "': the model has no such sensor" +
                     (left != sim_->leftOut(robot_).end() ? " (left out: " + left->second + ")" : "") +
                     "; its sensors: " + join(all) +
                     "; or odom, joints, scan, image, depth, imu, ground_truth");
    }
  }
  o.sensor = sensor;
  auto noOutput = [&](const std::string& outputs) {
    return EnvError("observation '" + what + "': sensor '" + sensor->name() + "' (" +
                    sensor->kind() + ") has no output '" + output + "'; it has " + outputs);
  };
  auto image = [&](const CameraSensor& c, SensorOutputs bits) {
    const CameraConfig& cfg = c.config();
    o.kind = Observation::Kind::kImage;
    o.outputs = bits;
    o.shape = {static_cast<std::size_t>(cfg.height), static_cast<std::size_t>(cfg.width),
               static_cast<std::size_t>(c.channels())};
    o.dtype = bytesPerChannel(cfg.format) == 2 ? 'H' : 'B';
    o.itemsize = bytesPerChannel(cfg.format);
  };
  if (const auto* lidar = dynamic_cast<const SimLidar*>(sensor)) {
    if (!output.empty() && output != "scan") throw noOutput("scan");
    o.kind = Observation::Kind::kScan;
    o.outputs = SimLidar::kScan;
    const RaySensorConfig& c = lidar->config();
    if (c.vertical_samples > 1) {
      o.shape = {static_cast<std::size_t>(c.vertical_samples), static_cast<std::size_t>(c.samples)};
    } else {
      o.shape = {static_cast<std::size_t>(c.samples)};
    }
    o.dtype = 'f';
    o.itemsize = 4;
  } else if (const auto* camera = dynamic_cast<const SimCamera*>(sensor)) {
    if (!output.empty() && output != "image") throw noOutput("image");
    image(camera->camera(), SimCamera::kImage);
  } else if (const auto* depth = dynamic_cast<const SimDepthCamera*>(sensor)) {
    if (output == "image") {
      const DepthCameraSensor& d = depth->camera();
      o.kind = Observation::Kind::kImage;
      o.outputs = SimDepthCamera::kImage;
      o.shape = {static_cast<std::size_t>(d.config().camera.height),
                 static_cast<std::size_t>(d.config().camera.width),
                 static_cast<std::size_t>(d.channels())};
      o.dtype = bytesPerChannel(d.config().camera.format) == 2 ? 'H' : 'B';
      o.itemsize = bytesPerChannel(d.config().camera.format);
    } else if (output.empty() || output == "depth") {
      const CameraConfig& c = depth->camera().config().camera;
      o.kind = Observation::Kind::kDepth;
      o.outputs = SimDepthCamera::kDepth;
      o.shape = {static_cast<std::size_t>(c.height), static_cast<std::size_t>(c.width)};
      o.dtype = 'f';
      o.itemsize = 4;
    } else {
      throw noOutput("depth, image");
    }
  } else if (const auto* multi = dynamic_cast<const SimMultiCamera*>(sensor)) {
    std::vector<std::string> indices;
    for (std::size_t i = 0; i < multi->size(); ++i) indices.push_back(std::to_string(i));
    std::size_t i = 0;
    for (; i < multi->size() && output != indices[i]; ++i) {
    }
    if (i == multi->size()) throw noOutput("one image per camera: " + join(indices));
    o.camera = static_cast<int>(i);
    image(multi->camera(i), SimMultiCamera::image(i));
  } else if (dynamic_cast<const SimImu*>(sensor)) {
    if (!output.empty() && output != "imu") throw noOutput("imu");
    o.kind = Observation::Kind::kImu;
    o.outputs = SimImu::kReading;
    o.shape = {10};
  } else if (dynamic_cast<const SimP3d*>(sensor)) {
    if (!output.empty() && output != "odom") throw noOutput("odom");
    o.kind = Observation::Kind::kGroundTruth;
    o.outputs = SimP3d::kReading;
    o.shape = {13};
  } else {
    throw EnvError("observation '" + what + "': sensor '" + sensor->name() + "' (" +
                   sensor->kind() + ") is not observable here yet");
  }
  return o;
}

std::vector<std::pair<std::string, std::string>> SimEnv::sensors() const {
  std::vector<std::pair<std::string, std::string>> out;
  for (const auto& s : sim_->sensors()) {
    if (s->link().model == robot_) out.emplace_back(s->name(), s->kind());
  }
  return out;
}

void SimEnv::setCommands(const double* values, std::size_t n) {
  if (n != commands_.size()) {
    throw EnvError("expected " + std::to_string(commands_.size()) + " controller commands, got " +
                   std::to_string(n));
  }
  for (std::size_t i = 0; i < n; ++i) {
    if (!std::isfinite(values[i])) {
      throw EnvError("controller '" + commands_[i].controller + "': command " +
                     std::to_string(values[i]) + " is not finite");
    }
  }
  for (std::size_t i = 0; i < n; ++i) sim_->setCommand(robot_, commands_[i].controller, values[i]);
}

void SimEnv::setAckermann(double speed, double steering) {
  if (!drive_) throw EnvError(drive_problem_);
  tc::AckermannDriveResult result;
  const tc::AckermannCommand c = drive_->command(speed, steering, time(), &result);
  if (result.rejected) {
    throw EnvError("Ackermann command (speed " + std::to_string(speed) + ", steering " +
                   std::to_string(steering) + ") is not finite");
  }
  const auto& names = drive_->controllers();
  sim_->setCommand(robot_, names[0], c.left_steer);
  sim_->setCommand(robot_, names[1], c.right_steer);
  sim_->setCommand(robot_, names[2], c.left_wheel_omega);
  sim_->setCommand(robot_, names[3], c.right_wheel_omega);
}

std::uint64_t SimEnv::step(int n) {
  const std::uint64_t before = contactCount();
  if (config_.timing) {
    for (int k = 0; k < n; ++k) {
      const double t0 = threadCpu();
      sim_->advance();
      const double t1 = threadCpu();
      sim_->sense();
      timing_.sensors += threadCpu() - t1;
      timing_.physics += t1 - t0;
    }
    const auto w0 = std::chrono::steady_clock::now();
    sim_->waitFrames();
    timing_.frames_wait +=
        std::chrono::duration<double>(std::chrono::steady_clock::now() - w0).count();
    timing_.steps += static_cast<std::uint64_t>(n);
  } else {
    for (int k = 0; k < n; ++k) {
      sim_->advance();
      sim_->sense();
    }
    sim_->waitFrames();
  }
  stampState();
  return contactCount() - before;
}

void SimEnv::reset(const std::optional<Eigen::Isometry3d>& X_WB, bool rest_on_ground) {
  // A simulation just built (reseed) starts from here as the node does from its start: the
  // sensors' first samples are the ones at time 0 below.
  if (initial_ || sim_->stepCount() != 0) sim_->resetSimulation();
  if (X_WB) {
    if (!X_WB->matrix().allFinite()) throw EnvError("reset pose is not finite");
    Eigen::Isometry3d X = *X_WB;
    if (rest_on_ground) X.translation().z() = depthBelowBase(model_, X.linear());
    const std::string bad = checkModelState(X, Twist());
    if (!bad.empty()) throw EnvError("reset pose: " + bad);
    EntityState base;
    base.X_WE = X;
    const Entities entities = sim_->entities();
    entities.setBase(entities.find(sim_->modelName(robot_), true), base, false);
  }
  if (drive_) drive_->reset();
  for (Observation& o : observations_) o.stamp = std::numeric_limits<double>::quiet_NaN();
  senseInitial();
}

void SimEnv::stampState() {
  for (Observation& o : observations_) {
    if (o.kind == Observation::Kind::kOdom || o.kind == Observation::Kind::kJoints) o.stamp = time();
  }
}

void SimEnv::reseed(std::uint64_t seed) { build(seed); }

void SimEnv::odom(double out[13]) const {
  // As toGroundTruth() of ros/state_msgs.h fills the node's ground_truth/odom.
  const EntityState s = sim_->modelState(robot_);
  const Eigen::Quaterniond q(s.X_WE.linear());
  const Eigen::Matrix3d R_BW = s.X_WE.linear().transpose();
  const Eigen::Vector3d v = R_BW * s.V_WE.linear;
  const Eigen::Vector3d w = R_BW * s.V_WE.angular;
  const Eigen::Vector3d p = s.X_WE.translation();
  const double values[13] = {p.x(), p.y(), p.z(), q.x(), q.y(), q.z(), q.w(),
                             v.x(), v.y(), v.z(), w.x(), w.y(), w.z()};
  std::memcpy(out, values, sizeof(values));
}

void SimEnv::read(std::size_t i, void* out) const {
  const Observation& o = observations_.at(i);
  const std::size_t bytes = o.bytes();
  auto copy = [&](const void* data, std::size_t n) {
    if (n == bytes) {
      std::memcpy(out, data, bytes);
    } else {
      std::memset(out, 0, bytes);  // not sampled yet (the stamp says NaN)
    }
  };
  switch (o.kind) {
    case Observation::Kind::kOdom:
      odom(static_cast<double*>(out));
      return;
    case Observation::Kind::kJoints: {
      JointStates js;
      sim_->jointStates(robot_, &js);
      double* d = static_cast<double*>(out);
      const std::size_t n = js.name.size();
      for (std::size_t j = 0; j < n && j < o.shape[1]; ++j) {
        d[j] = js.position[j];
        d[n + j] = js.velocity[j];
        d[2 * n + j] = js.effort[j];
      }
      return;
    }
    case Observation::Kind::kScan: {
      const auto& r = static_cast<const SimLidar*>(o.sensor)->ranges();
      copy(r.data(), r.size() * sizeof(float));
      return;
    }
    case Observation::Kind::kImage: {
      const std::vector<uint8_t>* img = nullptr;
      if (const auto* c = dynamic_cast<const SimCamera*>(o.sensor)) img = &c->camera().image();
      if (const auto* d = dynamic_cast<const SimDepthCamera*>(o.sensor)) img = &d->camera().image();
      if (const auto* m = dynamic_cast<const SimMultiCamera*>(o.sensor)) {
        img = &m->camera(static_cast<std::size_t>(o.camera)).image();
      }
      copy(img->data(), img->size());
      return;
    }
    case Observation::Kind::kDepth: {
      const auto& d = static_cast<const SimDepthCamera*>(o.sensor)->camera().depth();
      copy(d.data(), d.size() * sizeof(float));
      return;
    }
    case Observation::Kind::kImu: {
      const ImuReading& r = static_cast<const SimImu*>(o.sensor)->reading();
      double* d = static_cast<double*>(out);
      for (int k = 0; k < 4; ++k) d[k] = r.orientation_xyzw[k];
      for (int k = 0; k < 3; ++k) d[4 + k] = r.angular_velocity[k];
      for (int k = 0; k < 3; ++k) d[7 + k] = r.linear_acceleration[k];
      return;
    }
    case Observation::Kind::kGroundTruth: {
      const P3dReading& r = static_cast<const SimP3d*>(o.sensor)->reading();
      const double values[13] = {r.position.x(),    r.position.y(),    r.position.z(),
                                 r.orientation.x(), r.orientation.y(), r.orientation.z(),
                                 r.orientation.w(), r.linear.x(),      r.linear.y(),
                                 r.linear.z(),      r.angular.x(),     r.angular.y(),
                                 r.angular.z()};
      std::memcpy(out, values, sizeof(values));
      return;
    }
  }
}

std::vector<LinkContact> SimEnv::contacts() {
  std::vector<LinkContact> out, scratch;
  for (const std::string& link : sim_->entities().bodyLinks(robot_)) {
    sim_->linkContacts(LinkRef{robot_, link}, &scratch);
    out.insert(out.end(), scratch.begin(), scratch.end());
  }
  return out;
}

}  // namespace tianracer_sim
