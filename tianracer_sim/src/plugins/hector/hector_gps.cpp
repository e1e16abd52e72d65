// libhector_gazebo_ros_gps (hector_gps.h): GazeboRosGps::Load's parameters and Update's fix
// (hector_gazebo_plugins/src/gazebo_ros_gps.cpp, melodic-devel).
//
// Stricter than upstream: a reference latitude outside (-90, 90) (the east radius would be 0),
// a <status> other than -1..2 or a <service> other than 0..15 (NavSatStatus's values and bits)
// fail with the element and value.
#include "tianracer_sim/plugins/hector/hector_gps.h"

#include <cmath>

#include "tianracer_sim/common/text.h"
#include "tianracer_sim/model/plugin_reader.h"

namespace tianracer_sim {

namespace {

constexpr double kEquatorialRadius = 6378137.0;
constexpr double kFlattening = 1.0 / 298.257223563;
constexpr double kExcentricity2 = 2 * kFlattening - kFlattening * kFlattening;
constexpr double kDeg = M_PI / 180.0;

int readInteger(PluginReader& r, const std::string& key, int lo, int hi, int fallback,
                const std::string& what) {
  double v = fallback;
  if (!r.number(key, &v)) return fallback;
  if (v != std::floor(v) || v < lo || v > hi)
    r.fail("<" + key + "> '" + *r.text(key) + "' must be an integer " + std::to_string(lo) +
           ".." + std::to_string(hi) + " (" + what + ")");
  return static_cast<int>(v);
}

}  // namespace

HectorGpsConfig parseHectorGpsConfig(const SensorSpec& spec, const std::string& model_name,
                                     const WarningSink& warn) {
  const std::string context = "hector GPS plugin '" + spec.name + "' of model '" + model_name + "'";
  PluginReader r(hectorModelPlugin(spec, context), context, warn);
  HectorGpsConfig c;
  c.name = spec.name;
  r.robotNamespace(NamespaceRule::kAsGiven, &c.robot_namespace);
  r.text("bodyName", &c.link);
  readUseWorldSphericalCoordinates(r);
  c.frame_id = r.frame("frameId", "world");
  r.text("topicName", &c.topic_name);
  r.text("velocityTopicName", &c.velocity_topic_name);
  r.number("referenceLatitude", &c.reference_latitude);
  if (!(std::fabs(c.reference_latitude) < 90.0))
    r.fail("<referenceLatitude> " + formatNumber(c.reference_latitude) +
           " must be within (-90, 90) degrees");
  r.number("referenceLongitude", &c.reference_longitude);
  if (r.number("referenceHeading", &c.reference_heading)) c.reference_heading *= kDeg;
  r.number("referenceAltitude", &c.reference_altitude);
  c.status = readInteger(r, "status", -1, 2, c.status,
                         "NavSatStatus: -1 no fix, 0 fix, 1 SBAS, 2 GBAS");
  c.service = readInteger(r, "service", 0, 15, c.service,
                          "NavSatStatus bits: 1 GPS, 2 GLONASS, 4 COMPASS, 8 GALILEO");
  readErrorModel(r, "", &c.position);
  readErrorModel(r, "velocity", &c.velocity);
  readUpdateTimer(r, &c.timer);
  r.ignore({"alwaysOn"});
  r.finish();
  return c;
}

std::vector<SensorTopic> publishedTopics(const HectorGpsConfig& c) {
  return {{c.topic(), "sensor_msgs/NavSatFix", c.timer.rate()},
          {c.velocityTopic(), "geometry_msgs/Vector3Stamped", c.timer.rate()}};
}

GpsRadii gpsRadii(double latitude_deg) {
  const double s = std::sin(latitude_deg * kDeg);
  const double temp = 1.0 / (1.0 - kExcentricity2 * s * s);
  const double prime_vertical_radius = kEquatorialRadius * std::sqrt(temp);
  GpsRadii radii;
  radii.north = prime_vertical_radius * (1 - kExcentricity2) * temp;
  radii.east = prime_vertical_radius * std::cos(latitude_deg * kDeg);
  return radii;
}

HectorGpsReading gpsFix(const HectorGpsConfig& c, const GpsRadii& radii, const Eigen::Vector3d& p,
                        const Eigen::Vector3d& v) {
  const double ch = std::cos(c.reference_heading), sh = std::sin(c.reference_heading);
  HectorGpsReading out;
  out.latitude = c.reference_latitude + (ch * p.x() + sh * p.y()) / radii.north * 180.0 / M_PI;
  out.longitude = c.reference_longitude - (-sh * p.x() + ch * p.y()) / radii.east * 180.0 / M_PI;
  out.altitude = c.reference_altitude + p.z();
  out.velocity = Eigen::Vector3d(ch * v.x() + sh * v.y(), -sh * v.x() + ch * v.y(), v.z());
  out.status = c.status;
  out.service = c.service;
  for (int i = 0; i < 3; ++i) {
    out.position_covariance[4 * i] = c.position.drift[i] * c.position.drift[i] +
                                     c.position.gaussian_noise[i] * c.position.gaussian_noise[i];
  }
  return out;
}

HectorGps::HectorGps(HectorGpsConfig config)
    : config_(std::move(config)), radii_(gpsRadii(config_.reference_latitude)), rng_(config_.seed) {
  reset();
}

void HectorGps::reset() {
  config_.position.reset(rng_);
  config_.velocity.reset(rng_);
}

const HectorGpsReading& HectorGps::update(double dt, const LinkState& link) {
  const Eigen::Vector3d v = config_.velocity.apply(link.v_W, dt, rng_);
  const Eigen::Vector3d p = config_.position.apply(link.X_WL.translation(), dt, rng_);
  // A velocity drift integrates into the position error of the next update.
  config_.position.current_drift += dt * config_.velocity.current_drift;
  reading_ = gpsFix(config_, radii_, p, v);
  return reading_;
}

}  // namespace tianracer_sim
