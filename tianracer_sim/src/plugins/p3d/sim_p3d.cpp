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

SimP3d::SimP3d(const SimSensorSetup& setup, P3dConfig config)
    : SimSensor("p3d", config.name, setup.linkRef(config.link), setup.model_name),
      sensor_((config.seed = setup.seed + 401 + static_cast<std::uint64_t>(setup.index),
               setup.check_link(config.link),
               config.reference_link.empty() ? void() : setup.check_link(config.reference_link),
               config)) {
  const P3dConfig& c = sensor_.config();
  // Frames as the sim's others: tf_prefix on links, world as it is.
  frame_ = c.reference_link.empty() ? c.frame_name : resolveFrame(setup.tf_prefix, c.reference_link);
  child_ = resolveFrame(setup.tf_prefix, c.link);
  sampleAt(schedule_, c.name, c.update_rate);
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

}  // namespace tianracer_sim
