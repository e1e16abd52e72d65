// libhector_gazebo_ros_magnetic (hector_magnetic.h): GazeboRosMagnetic::Load's parameters and
// Update's field (hector_gazebo_plugins/src/gazebo_ros_magnetic.cpp, melodic-devel).
#include "tianracer_sim/plugins/hector/hector_magnetic.h"

#include <cmath>

#include "tianracer_sim/model/plugin_reader.h"

namespace tianracer_sim {

HectorMagneticConfig parseHectorMagneticConfig(const SensorSpec& spec,
                                               const std::string& model_name,
                                               const WarningSink& warn) {
  const std::string context =
      "hector magnetic plugin '" + spec.name + "' of model '" + model_name + "'";
  PluginReader r(hectorModelPlugin(spec, context), context, warn);
  HectorMagneticConfig c;
  c.name = spec.name;
  constexpr double kDeg = M_PI / 180.0;
  r.robotNamespace(NamespaceRule::kAsGiven, &c.robot_namespace);
  r.text("topicName", &c.topic_name);
  r.text("bodyName", &c.link);
  readUseWorldSphericalCoordinates(r);
  c.frame_id = r.frame("frameId", "");
  r.number("magnitude", &c.magnitude);
  if (r.number("referenceHeading", &c.reference_heading)) c.reference_heading *= kDeg;
  if (r.number("declination", &c.declination)) c.declination *= kDeg;
  if (r.number("inclination", &c.inclination)) c.inclination *= kDeg;
  r.boolean("useMagneticFieldMsgs", &c.use_magnetic_field_msgs);
  readErrorModel(r, "", &c.model);
  readUpdateTimer(r, &c.timer);
  r.ignore({"alwaysOn"});
  r.finish();
  return c;
}

std::vector<SensorTopic> publishedTopics(const HectorMagneticConfig& c) {
  return {{c.topic(),
           c.use_magnetic_field_msgs ? "sensor_msgs/MagneticField" : "geometry_msgs/Vector3Stamped",
           c.timer.rate()}};
}

Eigen::Vector3d HectorMagneticConfig::fieldWorld() const {
  // Gazebo's frame as north-west-up; heading and declination are compass angles.
  const double h = reference_heading - declination;
  return magnitude * Eigen::Vector3d(std::cos(inclination) * std::cos(h),
                                     std::cos(inclination) * std::sin(h), -std::sin(inclination));
}

HectorMagnetic::HectorMagnetic(HectorMagneticConfig config)
    : config_(std::move(config)), field_W_(config_.fieldWorld()), rng_(config_.seed) {
  reset();
}

void HectorMagnetic::reset() { config_.model.reset(rng_); }

const Eigen::Vector3d& HectorMagnetic::update(double dt, const Eigen::Matrix3d& R_WL) {
  field_ = config_.model.apply(R_WL.transpose() * field_W_, dt, rng_);
  return field_;
}

}  // namespace tianracer_sim
