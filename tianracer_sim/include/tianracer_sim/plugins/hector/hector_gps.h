// hector_gazebo_plugins' GPS, the model plugin libhector_gazebo_ros_gps (GazeboRosGps,
// src/gazebo_ros_gps.cpp, melodic-devel). ROS-free.
//
// At each update (default 4 Hz), dt since the last, p and v the link origin's world position
// and velocity, h the reference heading:
//  - v' = velocityModel(v, dt), p' = positionModel(p, dt) (hector_model.h), then the position
//    drift += dt * the velocity drift (a velocity offset integrates into the position);
//  - WGS84 radii at the reference latitude phi0 (a = 6378137, f = 1/298.257223563,
//    e2 = 2f - f^2): t = 1 / (1 - e2 sin^2 phi0), N = a sqrt(t), R_north = N (1 - e2) t,
//    R_east = N cos phi0;
//  - latitude  = lat0 + ( cos h x' + sin h y') / R_north * 180/pi,
//    longitude = lon0 - (-sin h x' + cos h y') / R_east  * 180/pi, altitude = alt0 + z';
//  - velocity (Vector3Stamped): ( cos h vx' + sin h vy', -sin h vx' + cos h vy', vz');
//  - position covariance diagonal (COVARIANCE_TYPE_DIAGONAL_KNOWN): drift^2 + gaussianNoise^2.
#ifndef TIANRACER_SIM_PLUGINS_HECTOR_HECTOR_GPS_H
#define TIANRACER_SIM_PLUGINS_HECTOR_HECTOR_GPS_H

#include <array>
#include <cstdint>
#include <random>
#include <string>
#include <vector>

#include <Eigen/Core>

#include "tianracer_sim/model/robot_model.h"
#include "tianracer_sim/plugins/hector/hector_model.h"
#include "tianracer_sim/plugins/link_data.h"
#include "tianracer_sim/plugins/sensor_topics.h"

namespace tianracer_sim {

struct HectorGpsConfig {
  std::string name;
  std::string link;             // <bodyName>; "" = the model's canonical link
  std::string robot_namespace;  // "" = "/"
  std::string frame_id = "world";  // <frameId> (upstream's default "/world")
  std::string topic_name = "fix";
  std::string velocity_topic_name = "fix_velocity";
  double reference_latitude = 49.9;   // degrees
  double reference_longitude = 8.9;   // degrees
  double reference_heading = 0.0;     // radians (given in degrees)
  double reference_altitude = 0.0;    // m
  int status = 0;                     // NavSatStatus STATUS_FIX
  int service = 0;                    // NavSatStatus service bits
  HectorErrorModel3 position, velocity;
  HectorUpdateTimer timer{0.25, 0.0};  // setUpdateRate(4.0) before Load
  std::uint64_t seed = 0;

  std::string topic() const { return resolveTopic(robot_namespace, topic_name); }
  std::string velocityTopic() const { return resolveTopic(robot_namespace, velocity_topic_name); }
};

HectorGpsConfig parseHectorGpsConfig(const SensorSpec& sensor, const std::string& model_name,
                                     const WarningSink& warn = {});
/// sensor_msgs/NavSatFix on topic(), geometry_msgs/Vector3Stamped on velocityTopic().
std::vector<SensorTopic> publishedTopics(const HectorGpsConfig& config);

/// The earth's radii (m) at a latitude (degrees), as gazebo_ros_gps computes them.
struct GpsRadii {
  double north = 0.0, east = 0.0;
};
GpsRadii gpsRadii(double latitude_deg);

struct HectorGpsReading {
  double latitude = 0.0, longitude = 0.0, altitude = 0.0;
  int status = 0, service = 0;
  std::array<double, 9> position_covariance{};
  Eigen::Vector3d velocity = Eigen::Vector3d::Zero();
};

/// The fix of a position (and velocity) given in the world frame, without noise: upstream's
/// conversion.
HectorGpsReading gpsFix(const HectorGpsConfig& config, const GpsRadii& radii,
                        const Eigen::Vector3d& position_W, const Eigen::Vector3d& velocity_W);

class HectorGps {
 public:
  explicit HectorGps(HectorGpsConfig config);
  const HectorGpsConfig& config() const { return config_; }
  void reset();
  const HectorGpsReading& update(double dt, const LinkState& link);
  const HectorGpsReading& reading() const { return reading_; }
  /// The models and the status, for dynamic_reconfigure.
  HectorErrorModel3& positionModel() { return config_.position; }
  HectorErrorModel3& velocityModel() { return config_.velocity; }
  void setStatus(int status, int service) {
    config_.status = status;
    config_.service = service;
  }

 private:
  HectorGpsConfig config_;
  GpsRadii radii_;
  std::mt19937_64 rng_;
  HectorGpsReading reading_;
};

}  // namespace tianracer_sim

#endif  // TIANRACER_SIM_PLUGINS_HECTOR_HECTOR_GPS_H
