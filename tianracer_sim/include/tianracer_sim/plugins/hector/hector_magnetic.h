// hector_gazebo_plugins' magnetometer, the model plugin libhector_gazebo_ros_magnetic
// (GazeboRosMagnetic, src/gazebo_ros_magnetic.cpp, melodic-devel). ROS-free.
//
// The field in the world (Gazebo's frame read as north-west-up; heading and declination are
// compass angles): B_W = m (cos i cos(h - d), cos i sin(h - d), -sin i), m the magnitude, h the
// reference heading, d the declination, i the inclination. At each update (default every
// step): B = sensorModel(R_WL^T B_W, dt) (hector_model.h), in the link's frame.
// Published as geometry_msgs/Vector3Stamped, or with <useMagneticFieldMsgs> true as
// sensor_msgs/MagneticField (covariance all 0, "unknown", as upstream).
#ifndef TIANRACER_SIM_PLUGINS_HECTOR_HECTOR_MAGNETIC_H
#define TIANRACER_SIM_PLUGINS_HECTOR_HECTOR_MAGNETIC_H

#include <cstdint>
#include <random>
#include <string>
#include <vector>

#include <Eigen/Geometry>

#include "tianracer_sim/model/robot_model.h"
#include "tianracer_sim/plugins/hector/hector_model.h"
#include "tianracer_sim/plugins/sensor_topics.h"

namespace tianracer_sim {

struct HectorMagneticConfig {
  std::string name;
  std::string link;             // <bodyName>; "" = the model's canonical link
  std::string robot_namespace;  // "" = "/"
  std::string frame_id;         // <frameId>; "" = the link's name
  std::string topic_name = "magnetic";
  double magnitude = 1.0;
  double reference_heading = 0.0;          // radians (given in degrees)
  double declination = 0.0;                // radians (given in degrees)
  double inclination = 60.0 * M_PI / 180;  // radians (given in degrees)
  bool use_magnetic_field_msgs = false;
  HectorErrorModel3 model;
  HectorUpdateTimer timer;  // every step unless given
  std::uint64_t seed = 0;

  std::string topic() const { return resolveTopic(robot_namespace, topic_name); }
  /// B_W.
  Eigen::Vector3d fieldWorld() const;
};

HectorMagneticConfig parseHectorMagneticConfig(const SensorSpec& sensor,
                                               const std::string& model_name,
                                               const WarningSink& warn = {});
/// geometry_msgs/Vector3Stamped (or sensor_msgs/MagneticField) on topic().
std::vector<SensorTopic> publishedTopics(const HectorMagneticConfig& config);

class HectorMagnetic {
 public:
  explicit HectorMagnetic(HectorMagneticConfig config);
  const HectorMagneticConfig& config() const { return config_; }
  void reset();
  const Eigen::Vector3d& update(double dt, const Eigen::Matrix3d& R_WL);
  const Eigen::Vector3d& field() const { return field_; }
  /// The model, for dynamic_reconfigure.
  HectorErrorModel3& model() { return config_.model; }

 private:
  HectorMagneticConfig config_;
  Eigen::Vector3d field_W_;
  std::mt19937_64 rng_;
  Eigen::Vector3d field_ = Eigen::Vector3d::Zero();
};

}  // namespace tianracer_sim

#endif  // TIANRACER_SIM_PLUGINS_HECTOR_HECTOR_MAGNETIC_H
