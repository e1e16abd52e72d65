// An IMU as Gazebo's <sensor type="imu"> with libgazebo_ros_imu_sensor, or the model plugin
// libgazebo_ros_imu (GazeboRosIMU), and what it measures. ROS-free.
//
// What it reports (sensor frame S = link frame * <pose>):
//  - orientation: R_WS as a quaternion (the world is the reference, REP 145; with
//    initialOrientationAsReference true, relative to the sensor's orientation at the first
//    step after start or reset), then rpyOffset applied in front: q = q_offset * q;
//  - angular velocity in S: the rotation of S over the last physics step, log(R_prev^T R) / dt;
//  - linear acceleration in S: the specific force R_WS^T (a_W - g_W), so +|g| up at rest.
//    a_W is the mean acceleration of the sensor's origin over the sample interval (velocity
//    change since the previous sample / interval), velocities being the origin's displacement
//    over one physics step / dt. Why finite differences: the physics exposes poses, and for
//    Bullet's semi-implicit Euler the displacement over a step is exactly v_{n+1} dt, so the
//    difference of two such velocities is the step's acceleration; the mean over the sample
//    interval is what a sampling IMU integrates, and it keeps contact impulses of single
//    steps from aliasing into the samples.
// Noise: per axis, SDF's <noise type="gaussian"> as Gazebo's GaussianNoiseModel: a bias drawn
// once from N(bias_mean, bias_stddev) with a random sign, plus N(mean, stddev) per sample
// ("gaussian_quantized" then rounds to <precision>); then the plugin's gaussianNoise, N(0, gn)
// on each component (libgazebo_ros_imu_sensor also on the quaternion's x, y, z, w, unnormalised,
// as Gazebo does). Covariances: diagonal gn^2 + stddev^2 of the axis (Gazebo writes gn^2 only).
#ifndef TIANRACER_SIM_PLUGINS_IMU_IMU_SENSOR_H
#define TIANRACER_SIM_PLUGINS_IMU_IMU_SENSOR_H

#include <array>
#include <cstdint>
#include <random>
#include <string>
#include <vector>

#include <Eigen/Geometry>

#include "tianracer_sim/model/robot_model.h"
#include "tianracer_sim/plugins/sensor_topics.h"

namespace tianracer_sim {

/// One axis's <noise>: type "none", "gaussian" or "gaussian_quantized".
struct ImuAxisNoise {
  std::string type = "none";
  double mean = 0.0, stddev = 0.0, bias_mean = 0.0, bias_stddev = 0.0;
  double precision = 0.0;  // gaussian_quantized only; 0 = none
  bool enabled() const { return type != "none"; }
};

struct ImuConfig {
  std::string name;  // <sensor name>, or the model plugin's name
  std::string link;
  Eigen::Isometry3d X_LS = Eigen::Isometry3d::Identity();
  double update_rate = 0.0;  // <update_rate> of the sensor (0 = every step)
  std::array<ImuAxisNoise, 3> rate_noise, accel_noise;  // x, y, z

  bool model_plugin = false;  // libgazebo_ros_imu (a <gazebo><plugin>, not a <sensor>)
  bool has_plugin = false;
  std::string plugin_filename;
  std::string robot_namespace;  // resolved: the plugin's, or its default
  std::string topic_name;
  std::string frame_name;
  std::string service_name;     // libgazebo_ros_imu's (std_srvs/Empty, always succeeds)
  double plugin_rate = 0.0;     // updateRateHZ / updateRate; 0 = every sensor update
  double gaussian_noise = 0.0;
  Eigen::Vector3d xyz_offset = Eigen::Vector3d::Zero();  // read; not applied (as Gazebo)
  Eigen::Vector3d rpy_offset = Eigen::Vector3d::Zero();
  bool initial_orientation_as_reference = false;
  std::uint64_t seed = 0;

  /// Samples per second: the slower of the sensor and the plugin rates (0 = every step).
  double publishRate() const;
  std::string topic() const { return resolveTopic(robot_namespace, topic_name); }
};

/// <sensor type="imu"> with (optionally) libgazebo_ros_imu_sensor. `model_name` is Gazebo's
/// default robotNamespace. Throws SensorError naming the sensor, element and value.
ImuConfig parseImuSensorConfig(const SensorSpec& sensor, const std::string& model_name,
                               const WarningSink& warn = {});
/// The model plugin libgazebo_ros_imu given as a SensorSpec of type "" whose only plugin is it
/// (see modelPluginSensor()). bodyName is required and becomes the link.
ImuConfig parseImuPluginConfig(const SensorSpec& sensor, const std::string& model_name,
                               const WarningSink& warn = {});
/// Throws SensorError for: a rate that is negative or not finite, a noise type not known,
/// negative standard deviations, a non-finite pose or offset.
void validate(const ImuConfig& config);
/// sensor_msgs/Imu on topic() at publishRate(); nothing without a gazebo_ros plugin.
std::vector<SensorTopic> publishedTopics(const ImuConfig& config);

/// A sample (orientation components as published: x, y, z, w).
struct ImuReading {
  Eigen::Vector4d orientation_xyzw{0.0, 0.0, 0.0, 1.0};
  Eigen::Vector3d angular_velocity = Eigen::Vector3d::Zero();
  Eigen::Vector3d linear_acceleration = Eigen::Vector3d::Zero();
  std::array<double, 9> orientation_covariance{};
  std::array<double, 9> angular_velocity_covariance{};
  std::array<double, 9> linear_acceleration_covariance{};
};

class ImuSensor {
 public:
  /// Validates (throws SensorError). gravity_W: the world's gravity (m/s^2).
  ImuSensor(ImuConfig config, const Eigen::Vector3d& gravity_W);
  /// The world's gravity from now on (gazebo-classic ImuSensor::UpdateImpl reads the physics
  /// engine's gravity at each update).
  void setGravity(const Eigen::Vector3d& gravity_W) { gravity_W_ = gravity_W; }

  const ImuConfig& config() const { return config_; }
  /// Forget the motion history (after a reset or a teleport). Noise generator and biases stay.
  void reset();
  /// Every physics step, after it: the pose of the sensor's link at sim time t.
  void record(double t, const Eigen::Isometry3d& X_WL);
  /// A sample at the last recorded time, noise included; starts the next sample interval.
  const ImuReading& read();
  /// Starts the next sample interval without producing a sample (nobody listening).
  void skip();
  /// The bias drawn for each axis (rates, then accelerations).
  const std::array<double, 6>& biases() const { return bias_; }

 private:
  double noisy(double value, const ImuAxisNoise& noise, double bias);

  ImuConfig config_;
  Eigen::Vector3d gravity_W_;
  Eigen::Quaterniond q_offset_;
  std::mt19937_64 rng_;
  std::array<double, 6> bias_{};
  ImuReading reading_;
  // Motion history.
  int steps_ = 0;  // recorded steps since reset (saturates at 2)
  double t_ = 0.0;
  Eigen::Vector3d p_W_ = Eigen::Vector3d::Zero(), v_W_ = Eigen::Vector3d::Zero();
  Eigen::Matrix3d R_WS_ = Eigen::Matrix3d::Identity();
  Eigen::Vector3d w_S_ = Eigen::Vector3d::Zero();
  Eigen::Quaterniond q_ref_inv_ = Eigen::Quaterniond::Identity();
  bool have_sample_ = false;
  double t_sample_ = 0.0;
  Eigen::Vector3d v_sample_ = Eigen::Vector3d::Zero();
};

}  // namespace tianracer_sim

#endif  // TIANRACER_SIM_PLUGINS_IMU_IMU_SENSOR_H
