// libhector_gazebo_ros_imu (hector_imu.h): GazeboRosIMU::Load's parameters and Update's
// measurement (hector_gazebo_plugins/src/gazebo_ros_imu.cpp, melodic-devel).
#include "tianracer_sim/plugins/hector/hector_imu.h"

#include <algorithm>
#include <cmath>

#include "tianracer_sim/model/plugin_reader.h"

namespace tianracer_sim {

HectorImuConfig parseHectorImuConfig(const SensorSpec& spec, const std::string& model_name,
                                     const WarningSink& warn) {
  const std::string context = "hector IMU plugin '" + spec.name + "' of model '" + model_name + "'";
  PluginReader r(hectorModelPlugin(spec, context), context, warn);
  HectorImuConfig c;
  c.name = spec.name;
  r.robotNamespace(NamespaceRule::kAsGiven, &c.robot_namespace);
  r.text("bodyName", &c.link);
  c.frame_id = r.frame("frameId", "");
  r.text("topicName", &c.topic_name);
  c.bias_topic_name = c.topic_name.empty() ? "" : c.topic_name + "/bias";
  r.text("biasTopicName", &c.bias_topic_name);
  c.service_name = c.topic_name + "/calibrate";
  r.text("serviceName", &c.service_name);
  readErrorModel(r, "accel", &c.accel);
  readErrorModel(r, "rate", &c.rate);
  readErrorModel(r, "yaw", &c.yaw);
  // The old gazebo_ros_imu name: a non-zero gaussianNoise is both models' noise.
  double gn = 0.0;
  if (r.number("gaussianNoise", &gn, true) && gn != 0.0) {
    c.accel.gaussian_noise.setConstant(gn);
    c.rate.gaussian_noise.setConstant(gn);
  }
  r.vector3("xyzOffset", &c.xyz_offset);
  r.vector3("rpyOffset", &c.rpy_offset);
  readUpdateTimer(r, &c.timer);
  r.ignore({"alwaysOn"});
  r.finish();
  return c;
}

std::vector<SensorTopic> publishedTopics(const HectorImuConfig& c) {
  std::vector<SensorTopic> topics;
  // Upstream advertises nothing on an empty name.
  if (!c.topic_name.empty()) topics.push_back({c.topic(), "sensor_msgs/Imu", c.timer.rate()});
  if (!c.bias_topic_name.empty())
    topics.push_back({c.biasTopic(), "sensor_msgs/Imu", c.timer.rate()});
  return topics;
}

namespace {

// ignition's Quaterniond(roll, pitch, yaw): Rz(yaw) Ry(pitch) Rx(roll).
Eigen::Quaterniond euler(const Eigen::Vector3d& rpy) {
  return Eigen::AngleAxisd(rpy.z(), Eigen::Vector3d::UnitZ()) *
         Eigen::AngleAxisd(rpy.y(), Eigen::Vector3d::UnitY()) *
         Eigen::AngleAxisd(rpy.x(), Eigen::Vector3d::UnitX());
}

void setXyzw(const Eigen::Quaterniond& q, Eigen::Vector4d* out) {
  *out = Eigen::Vector4d(q.x(), q.y(), q.z(), q.w());
}

}  // namespace

HectorImu::HectorImu(HectorImuConfig config)
    : config_(std::move(config)), rng_(config_.seed), q_offset_(euler(config_.rpy_offset)) {
  // Filled once at Load, as upstream ("constant covariance matrix").
  ImuReading& m = reading_.imu;
  for (int i = 0; i < 3; ++i) {
    m.angular_velocity_covariance[4 * i] = std::pow(config_.rate.gaussian_noise[i], 2);
    m.linear_acceleration_covariance[4 * i] = std::pow(config_.accel.gaussian_noise[i], 2);
  }
  reset();
}

void HectorImu::reset() {
  orientation_ = Eigen::Quaterniond::Identity();
  velocity_.setZero();
  accel_.setZero();
  config_.accel.reset(rng_);
  config_.rate.reset(rng_);
  config_.yaw.reset(rng_);
}

const HectorImuReading& HectorImu::update(double dt, const LinkState& link,
                                          const Eigen::Vector3d& g_W) {
  const Eigen::Quaterniond q_pose(link.X_WL.linear());
  const Eigen::Quaterniond rot = (q_offset_ * q_pose).normalized();
  const double g = g_W.norm();

  if (dt > 0.0) accel_ = rot.conjugate() * ((link.v_W - velocity_) / dt - g_W);
  velocity_ = link.v_W;

  Eigen::Quaterniond delta = orientation_.conjugate() * rot;
  orientation_ = rot;
  if (dt > 0.0) {
    if (delta.w() < 0.0) delta.coeffs() = -delta.coeffs();  // the shortest rotation
    const double s = delta.vec().norm();
    const Eigen::Vector3d turn =
        s > 0.0 ? Eigen::Vector3d(2.0 * std::atan2(s, delta.w()) * delta.vec() / s)
                : Eigen::Vector3d::Zero();
    rate_ = q_offset_.conjugate() * (turn / dt);
  }

  accel_ = config_.accel.apply(accel_, dt, rng_);
  rate_ = config_.rate.apply(rate_, dt, rng_);
  config_.yaw.update(dt, rng_);

  // The pseudo AHRS: accelerometer bias as roll and pitch error, the yaw model's bias as yaw.
  const Eigen::Vector3d drift_W = q_pose * config_.accel.bias();
  const double yaw_error = config_.yaw.bias()[0];
  Eigen::Quaterniond tilt = Eigen::Quaterniond::Identity();
  if (g > 0.0) tilt = Eigen::Quaterniond(1.0, 0.5 * drift_W.y() / g, 0.5 * -drift_W.x() / g, 0.0);
  const Eigen::Quaterniond error =
      (Eigen::Quaterniond(std::cos(yaw_error / 2), 0.0, 0.0, std::sin(yaw_error / 2)) * tilt)
          .normalized();
  const Eigen::Quaterniond published = error * rot;

  ImuReading& m = reading_.imu;
  setXyzw(published, &m.orientation_xyzw);
  m.angular_velocity = rate_;
  m.linear_acceleration = accel_;
  const HectorErrorModel3& a = config_.accel;
  const HectorErrorModel3& w = config_.rate;
  m.orientation_covariance[8] = std::pow(config_.yaw.gaussian_noise[0], 2);
  m.orientation_covariance[0] = g > 0.0 ? std::pow(a.gaussian_noise.x() / g, 2) : -1.0;
  m.orientation_covariance[4] = g > 0.0 ? std::pow(a.gaussian_noise.y() / g, 2) : -1.0;

  ImuReading& b = reading_.bias;
  setXyzw(error, &b.orientation_xyzw);
  b.angular_velocity = w.bias();
  b.linear_acceleration = a.bias();
  return reading_;
}

}  // namespace tianracer_sim
