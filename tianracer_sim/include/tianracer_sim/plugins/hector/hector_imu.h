// hector_gazebo_plugins' IMU, the model plugin libhector_gazebo_ros_imu (GazeboRosIMU,
// src/gazebo_ros_imu.cpp, melodic-devel), and what it measures. ROS-free.
//
// At each update (UpdateTimer, default every step), with dt the time since the last one and q
// the link's orientation, q_o the rpyOffset's (roll, pitch, yaw as ignition's Euler):
//  - rot = q_o * q;  with dt > 0: accel = rot^-1 ((v - v_last) / dt - g), v the link origin's
//    world velocity (so +|g| up at rest); rate = q_o^-1 (angle * axis of q_last^-1 rot) / dt;
//    with dt = 0 (the first update) both keep their last values (0 after a reset);
//  - accel = accelModel(accel, dt), rate = rateModel(rate, dt), yawModel.update(dt)
//    (hector_model.h), in that order;
//  - orientation error (a pseudo AHRS): d = q * accelBias (the accelerometer bias in the world),
//    e = (cos(yawBias/2), 0, 0, sin(yawBias/2)) * (1, d.y / 2|g|, -d.x / 2|g|, 0), normalised;
//    the orientation published is e * rot;
//  - covariances: orientation [0], [4] accel gn.x^2 / |g|^2, gn.y^2 / |g|^2 (-1 without
//    gravity), [8] yaw gn^2, at each update; rates and accelerations diag(gn^2) of their
//    models as loaded (upstream fills them once: a reconfigured noise does not change them);
//  - the bias message: orientation e, angular_velocity the rate bias, linear_acceleration the
//    accel bias (drift + offset), covariances 0.
// Differences: the rate's rotation angle is 2 atan2(|v|, w) of the shortest rotation (upstream
// 2 acos(w) of the quaternion as it comes, and ignition's Normalize leaves axes shorter than
// 1e-6 unnormalised); without gravity the roll/pitch error is left out (upstream divides by 0).
#ifndef TIANRACER_SIM_PLUGINS_HECTOR_HECTOR_IMU_H
#define TIANRACER_SIM_PLUGINS_HECTOR_HECTOR_IMU_H

#include <cstdint>
#include <random>
#include <string>
#include <vector>

#include <Eigen/Geometry>

#include "tianracer_sim/model/robot_model.h"
#include "tianracer_sim/plugins/hector/hector_model.h"
#include "tianracer_sim/plugins/imu/imu_sensor.h"  // ImuReading
#include "tianracer_sim/plugins/link_data.h"
#include "tianracer_sim/plugins/sensor_topics.h"

namespace tianracer_sim {

struct HectorImuConfig {
  std::string name;             // the plugin's name
  std::string link;             // <bodyName>; "" = the model's canonical link
  std::string robot_namespace;  // <robotNamespace>, "" = "/" (no model-name default)
  std::string frame_id;         // <frameId>; "" = the link's name
  std::string topic_name = "imu";
  std::string bias_topic_name;  // <biasTopicName>; default <topicName>/bias ("" = none)
  std::string service_name;     // <serviceName>; default <topicName>/calibrate ("" = none)
  HectorUpdateTimer timer;      // every step unless given
  HectorErrorModel3 accel, rate;
  HectorErrorModel1 yaw;
  Eigen::Vector3d xyz_offset = Eigen::Vector3d::Zero();  // read, unused (as upstream)
  Eigen::Vector3d rpy_offset = Eigen::Vector3d::Zero();
  std::uint64_t seed = 0;

  std::string topic() const { return resolveTopic(robot_namespace, topic_name); }
  std::string biasTopic() const { return resolveTopic(robot_namespace, bias_topic_name); }
  std::string service() const { return resolveTopic(robot_namespace, service_name); }
};

/// The model plugin given as a SensorSpec of type "" (modelPluginSensor()). Throws SensorError
/// at the <plugin>'s line naming the plugin, element and value.
HectorImuConfig parseHectorImuConfig(const SensorSpec& sensor, const std::string& model_name,
                                     const WarningSink& warn = {});
/// sensor_msgs/Imu on topic() and, with a bias topic, on biasTopic(), at the timer's rate.
std::vector<SensorTopic> publishedTopics(const HectorImuConfig& config);

struct HectorImuReading {
  ImuReading imu;
  ImuReading bias;
};

class HectorImu {
 public:
  explicit HectorImu(HectorImuConfig config);
  const HectorImuConfig& config() const { return config_; }
  /// Reset(): orientation, velocity and acceleration forgotten, the models' drifts drawn anew.
  void reset();
  /// An update: `dt` since the last (0 at the first), the link's state, the world's gravity.
  const HectorImuReading& update(double dt, const LinkState& link, const Eigen::Vector3d& g_W);
  const HectorImuReading& reading() const { return reading_; }
  /// The calibrate service: the rate drift set to 0.
  void calibrate() { config_.rate.reset(Eigen::Vector3d::Zero()); }
  /// set_accel_bias / set_rate_bias: the model's drift set to `bias`.
  void setAccelBias(const Eigen::Vector3d& bias) { config_.accel.reset(bias); }
  void setRateBias(const Eigen::Vector3d& bias) { config_.rate.reset(bias); }
  /// The models, for dynamic_reconfigure (upstream's SensorModel_::dynamicReconfigureCallback).
  HectorErrorModel3& accelModel() { return config_.accel; }
  HectorErrorModel3& rateModel() { return config_.rate; }
  HectorErrorModel1& yawModel() { return config_.yaw; }

 private:
  HectorImuConfig config_;  // holds the models' state
  std::mt19937_64 rng_;
  Eigen::Quaterniond q_offset_;
  Eigen::Quaterniond orientation_ = Eigen::Quaterniond::Identity();
  Eigen::Vector3d velocity_ = Eigen::Vector3d::Zero();
  Eigen::Vector3d accel_ = Eigen::Vector3d::Zero();
  Eigen::Vector3d rate_ = Eigen::Vector3d::Zero();
  HectorImuReading reading_;
};

}  // namespace tianracer_sim

#endif  // TIANRACER_SIM_PLUGINS_HECTOR_HECTOR_IMU_H
