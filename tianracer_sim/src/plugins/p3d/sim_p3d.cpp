#include "tianracer_sim/plugins/p3d/sim_p3d.h"

#include <tianracer_control/naming.h>

#include "tianracer_sim/plugins/sensor_registry.h"

namespace tianracer_sim {

namespace {

std::unique_ptr<SimSensor> makeP3d(const SimSensorSetup& setup) {
  return std::make_unique<SimP3d>(setup, parseP3dConfig(*setup.spec, setup.model_name, setup.warn));
}

}  // namespace

const SensorKind& p3dKind() {
  static const SensorKind kind = {"p3d", {}, {"libgazebo_ros_p3d.so"}, &topicsOf<parseP3dConfig>, &makeP3d};
  return kind;
}
TIANRACER_SENSOR_KIND(p3dKind);

namespace {

P3dConfig placedP3d(const SimSensorSetup& setup, P3dConfig config) {
  config.seed = setup.seed + 401 + static_cast<std::uint64_t>(setup.index);
  setup.check_link(config.link);
  if (!config.reference_link.empty()) setup.check_link(config.reference_link);
  return config;
}

}  // namespace

SimP3d::SimP3d(const SimSensorSetup& setup, P3dConfig config)
    : SimCoreSensor("p3d", setup, config.name, config.link, P3dSensor(placedP3d(setup, config)),
                    config.update_rate) {
  const P3dConfig& c = core_.config();
  // Frames as the sim's others: tf_prefix on links, world as it is.
  frame_ = c.reference_link.empty() ? c.frame_name : resolveFrame(setup.tf_prefix, c.reference_link);
  child_ = resolveFrame(setup.tf_prefix, c.link);
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

void SimP3d::track(double t, SensorWorld& world) {
  const P3dConfig& c = core_.config();
  track(t, world, c.link, &body_);
  if (!c.reference_link.empty()) track(t, world, c.reference_link, &reference_);
}

void SimP3d::sample(SensorOutputs, SensorWorld&) {
  const P3dConfig& c = core_.config();
  setOutput(core_.measure(body_.state(), c.reference_link.empty() ? nullptr : &reference_.state()));
}

void SimP3d::forget() {
  body_.reset();
  reference_.reset();
}

}  // namespace tianracer_sim
