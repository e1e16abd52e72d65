#include "tianracer_sim/plugins/bumper/sim_bumper.h"

#include <exception>

#include <tianracer_control/naming.h>

#include "tianracer_sim/plugins/sensor_registry.h"

namespace tianracer_sim {

namespace {

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

}  // namespace

const SensorKind& bumperKind() {
  static const SensorKind kind = {"bumper", {"contact"}, {"libgazebo_ros_bumper.so"}, &topicsOf<parseBumperConfig>, &makeBumper};
  return kind;
}
TIANRACER_SENSOR_KIND(bumperKind);

SimBumper::SimBumper(const SimSensorSetup& setup, BumperConfig config)
    : SimSensor("bumper", config.name, setup.linkRef(config.link), setup.model_name),
      config_(std::move(config)) {
  setup.check_link(config_.link);
  const bool world = config_.frame_name == "world" || config_.frame_name == "map";
  if (!world) {
    try {
      setup.check_link(config_.frame_name);
    } catch (const std::exception&) {
      setup.fail("contact sensor '" + config_.name + "' of model '" + setup.model_name +
                 "': <frameName> '" + config_.frame_name +
                 "' is neither world nor a link of the model");
    }
    frame_link_ = config_.frame_name;
  }
  frame_id_ = world ? config_.frame_name : resolveFrame(setup.tf_prefix, config_.frame_name);
  sampleAt(schedule_, config_.name, config_.update_rate);
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

}  // namespace tianracer_sim
