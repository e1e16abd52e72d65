#include "tianracer_sim/plugins/hector/sim_hector.h"

#include <urdf_model/model.h>

#include <tianracer_control/naming.h>

#include "tianracer_sim/plugins/sensor_registry.h"

namespace tianracer_sim {

namespace {

// Gazebo's Model::GetLink() without a name: the canonical link, which for a URDF robot is its
// root link. A world model is not told its canonical link here: it must name <bodyName>.
// A <bodyName> the model lacks: upstream's ROS_FATAL, here a message at the plugin's line.
std::string bodyLink(const SimSensorSetup& setup, const std::string& link,
                     const std::string& what) {
  const std::string who = what + " '" + setup.spec->name + "' of model '" + setup.model_name + "'";
  if (link.empty()) {
    if (setup.urdf && setup.urdf->getRoot()) return setup.urdf->getRoot()->name;
    setup.fail(who + ": no <bodyName>, and a world model's canonical link is not known here; "
               "give <bodyName>");
  }
  try {
    setup.check_link(link);
  } catch (const std::exception&) {
    setup.fail(who + ": <bodyName> '" + link + "' is not a link of the model");
  }
  return link;
}

// Frames as the sim's others: the tf_prefix on links, "world" as it is.
std::string frameOf(const SimSensorSetup& setup, const std::string& frame) {
  return frame == "world" ? frame : resolveFrame(setup.tf_prefix, frame);
}

std::uint64_t seedOf(const SimSensorSetup& setup, std::uint64_t kind) {
  return setup.seed + kind + static_cast<std::uint64_t>(setup.index);
}

std::unique_ptr<SimSensor> makeHectorImu(const SimSensorSetup& setup) {
  HectorImuConfig c = parseHectorImuConfig(*setup.spec, setup.model_name, setup.warn);
  if (c.topic_name.empty() && c.bias_topic_name.empty()) return nullptr;  // nothing advertised
  c.link = bodyLink(setup, c.link, "hector IMU plugin");
  if (c.frame_id.empty()) c.frame_id = c.link;
  c.seed = seedOf(setup, 701);
  return std::make_unique<SimHectorImu>(setup, std::move(c));
}

std::unique_ptr<SimSensor> makeGps(const SimSensorSetup& setup) {
  HectorGpsConfig c = parseHectorGpsConfig(*setup.spec, setup.model_name, setup.warn);
  c.link = bodyLink(setup, c.link, "hector GPS plugin");
  c.seed = seedOf(setup, 801);
  return std::make_unique<SimHectorGps>(setup, std::move(c));
}

std::unique_ptr<SimSensor> makeMagnetic(const SimSensorSetup& setup) {
  HectorMagneticConfig c = parseHectorMagneticConfig(*setup.spec, setup.model_name, setup.warn);
  c.link = bodyLink(setup, c.link, "hector magnetic plugin");
  if (c.frame_id.empty()) c.frame_id = c.link;
  c.seed = seedOf(setup, 901);
  return std::make_unique<SimHectorMagnetic>(setup, std::move(c));
}

std::unique_ptr<SimSensor> makeSonar(const SimSensorSetup& setup) {
  HectorSonarConfig c = parseHectorSonarConfig(*setup.spec, setup.warn);
  c.seed = seedOf(setup, 1001);
  c.frame_id = frameOf(setup, c.frame_id);
  return std::make_unique<SimHectorSonar>(setup, std::move(c));
}

SensorOutputs imuOutputs(const HectorImuConfig& c) {
  return (c.topic_name.empty() ? 0 : SimHectorImu::kImu) |
         (c.bias_topic_name.empty() ? 0 : SimHectorImu::kBias);
}

}  // namespace

const SensorKind& hectorImuKind() {
  static const SensorKind kind = {"hector_imu", {}, {"libhector_gazebo_ros_imu.so"},
                                  &topicsOf<parseHectorImuConfig>, &makeHectorImu};
  return kind;
}
TIANRACER_SENSOR_KIND(hectorImuKind);

const SensorKind& hectorGpsKind() {
  static const SensorKind kind = {"hector_gps", {}, {"libhector_gazebo_ros_gps.so"},
                                  &topicsOf<parseHectorGpsConfig>, &makeGps};
  return kind;
}
TIANRACER_SENSOR_KIND(hectorGpsKind);

const SensorKind& hectorMagneticKind() {
  static const SensorKind kind = {"hector_magnetic", {}, {"libhector_gazebo_ros_magnetic.so"},
                                  &topicsOf<parseHectorMagneticConfig>, &makeMagnetic};
  return kind;
}
TIANRACER_SENSOR_KIND(hectorMagneticKind);

const SensorKind& hectorSonarKind() {
  // A ray sensor (Gazebo casts the plugin's parent to RaySensor: gpu_ray is refused there and
  // here, by the parser's message).
  static const SensorKind kind = {"hector_sonar", {"ray", "gpu_ray"},
                                  {"libhector_gazebo_ros_sonar.so"},
                                  &topicsOf<parseHectorSonarConfig>, &makeSonar};
  return kind;
}
TIANRACER_SENSOR_KIND(hectorSonarKind);

SimHectorPlugin::SimHectorPlugin(const std::string& kind, const SimSensorSetup& setup,
                                 const std::string& name, const std::string& link,
                                 const HectorUpdateTimer& timer, SensorOutputs outputs)
    : SimSensor(kind, name, setup.linkRef(link), setup.model_name), clock_(timer),
      outputs_(outputs) {
  setup.check_link(link);
  stat().name = name;
  stat().target = timer.rate();
}

SensorOutputs SimHectorPlugin::update(double t, SensorWorld& world) {
  LinkState exact;
  if (world.linkState(link(), &exact)) {
    motion_.set(t, exact);
  } else {
    motion_.record(t, world.linkPose(link()));
  }
  if (!clock_.due(t)) return 0;
  t_ = t;
  gravity_ = world.gravity();
  return outputs_;
}

void SimHectorPlugin::restart(double t) {
  clock_.restart(t);
  motion_.reset();
  resetCore();
}

SimHectorImu::SimHectorImu(const SimSensorSetup& setup, HectorImuConfig config)
    : SimHectorPlugin("hector_imu", setup, config.name, config.link, config.timer,
                      imuOutputs(config)),
      imu_(config), frame_(frameOf(setup, config.frame_id)) {}

SimHectorGps::SimHectorGps(const SimSensorSetup& setup, HectorGpsConfig config)
    : SimHectorPlugin("hector_gps", setup, config.name, config.link, config.timer,
                      kFix | kVelocity),
      gps_(config), frame_(frameOf(setup, config.frame_id)) {}

SimHectorMagnetic::SimHectorMagnetic(const SimSensorSetup& setup, HectorMagneticConfig config)
    : SimHectorPlugin("hector_magnetic", setup, config.name, config.link, config.timer, kField),
      magnetic_(config), frame_(frameOf(setup, config.frame_id)) {}

SimHectorSonar::SimHectorSonar(const SimSensorSetup& setup, HectorSonarConfig config)
    : SimSensor("hector_sonar", config.ray.name, setup.linkRef(config.ray.link), setup.model_name),
      config_(std::move(config)), rng_(config_.seed), clock_(config_.timer) {
  setup.check_link(config_.ray.link);
  stat().name = config_.ray.name;
  stat().target = config_.timer.rate();
  config_.model.reset(rng_);
}

SensorOutputs SimHectorSonar::update(double t, SensorWorld&) {
  if (!clock_.due(t)) return 0;
  t_ = t;
  return kRange;
}

void SimHectorSonar::sample(SensorOutputs, SensorWorld& world) {
  const double dt = clock_.tick(t_);
  const Scene& scene = world.scene();
  shapeRanges(config_.ray, world.caster(), scene, world.linkPose(link()) * config_.ray.X_LS,
              &buffers_, &ranges_);
  reading_ = sonarReading(config_, ranges_, dt, &config_.model, rng_);
}

void SimHectorSonar::restart(double t) {
  clock_.restart(t);
  config_.model.reset(rng_);
}

}  // namespace tianracer_sim
