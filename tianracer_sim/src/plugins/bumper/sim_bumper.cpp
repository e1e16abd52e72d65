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
    : SimCoreSensor("bumper", setup, config.name, config.link, config, config.update_rate) {
  const BumperConfig& c = core_;
  setup.check_link(c.link);
  const bool world = c.frame_name == "world" || c.frame_name == "map";
  if (!world) {
    try {
      setup.check_link(c.frame_name);
    } catch (const std::exception&) {
      setup.fail("contact sensor '" + c.name + "' of model '" + setup.model_name +
                 "': <frameName> '" + c.frame_name + "' is neither world nor a link of the model");
    }
    frame_link_ = c.frame_name;
  }
  frame_id_ = world ? c.frame_name : resolveFrame(setup.tf_prefix, c.frame_name);
  setOutput(states_);
}

void SimBumper::sample(SensorOutputs, SensorWorld& world) {
  world.linkContacts(link(), &contacts_);
  const Eigen::Isometry3d X_WF = frame_link_.empty()
                                     ? Eigen::Isometry3d::Identity()
                                     : world.linkPose(LinkRef{link().model, frame_link_});
  // The impulses come from the step just taken, with the step size now in force.
  bumperStates(contacts_, X_WF, world.dt(), &states_);
}

}  // namespace tianracer_sim
