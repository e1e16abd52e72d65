#include "tianracer_sim/plugins/p3d/p3d.h"

#include "tianracer_sim/model/plugin_reader.h"

namespace tianracer_sim {

P3dConfig parseP3dConfig(const SensorSpec& spec, const std::string& model_name,
                         const WarningSink& warn) {
  const std::string what = "p3d plugin '" + spec.name + "' of model '" + model_name + "'";
  if (spec.plugins.size() != 1) throw SensorError(what + ": expected one plugin");
  const PluginSpec& p = spec.plugins.front();
  PluginReader r(p, what, warn);
  P3dConfig c;
  c.name = spec.name;
  r.robotNamespace(NamespaceRule::kAsGiven, &c.robot_namespace);
  r.text("bodyName", &c.link);
  r.text("topicName", &c.topic_name);
  c.frame_name = r.frame("frameName", "world");
  r.number("updateRate", &c.update_rate, true);
  r.number("gaussianNoise", &c.gaussian_noise, true);
  // gazebo_ros_p3d reads xyzOffsets/rpyOffsets; models often write the IMU plugin's singular
  // (the plural wins when both are given).
  for (const char* key : {"xyzOffset", "xyzOffsets"}) r.vector3(key, &c.xyz_offsets);
  for (const char* key : {"rpyOffset", "rpyOffsets"}) r.vector3(key, &c.rpy_offsets);
  r.ignore({"alwaysOn"});
  r.finish();
  if (c.link.empty()) r.fail("<bodyName> is missing (Gazebo does not load the plugin without it)");
  if (c.topic_name.empty())
    r.fail("<topicName> is missing (Gazebo does not load the plugin without it)");
  if (c.frame_name != "world" && c.frame_name != "map") c.reference_link = c.frame_name;
  return c;
}

std::vector<SensorTopic> publishedTopics(const P3dConfig& c) {
  return {{c.topic(), "nav_msgs/Odometry", c.update_rate}};
}

const LinkState& LinkMotion::record(double t, const Eigen::Isometry3d& X_WL) {
  if (steps_ > 0 && t > t_) {
    const double dt = t - t_;
    state_.v_W = (X_WL.translation() - state_.X_WL.translation()) / dt;
    const Eigen::AngleAxisd turn(state_.X_WL.linear().transpose() * X_WL.linear());
    state_.w_W = state_.X_WL.linear() * (turn.axis() * (turn.angle() / dt));
  } else if (steps_ == 0) {
    state_.v_W.setZero();
    state_.w_W.setZero();
  }
  state_.X_WL = X_WL;
  t_ = t;
  steps_ = 1;
  return state_;
}

const LinkState& LinkMotion::set(double t, const LinkState& state) {
  state_ = state;
  t_ = t;
  steps_ = 1;
  return state_;
}

P3dSensor::P3dSensor(P3dConfig config) : config_(std::move(config)), rng_(config_.seed) {
  q_offset_ = Eigen::AngleAxisd(config_.rpy_offsets.z(), Eigen::Vector3d::UnitZ()) *
              Eigen::AngleAxisd(config_.rpy_offsets.y(), Eigen::Vector3d::UnitY()) *
              Eigen::AngleAxisd(config_.rpy_offsets.x(), Eigen::Vector3d::UnitX());
  reading_.variance = config_.gaussian_noise * config_.gaussian_noise;
}

const P3dReading& P3dSensor::measure(const LinkState& body, const LinkState* reference) {
  P3dReading& r = reading_;
  Eigen::Quaterniond q(body.X_WL.linear());
  r.position = body.X_WL.translation();
  r.linear = body.v_W;
  r.angular = body.w_W;
  if (reference) {
    const Eigen::Matrix3d R_RW = reference->X_WL.linear().transpose();
    r.position = R_RW * (r.position - reference->X_WL.translation());
    q = Eigen::Quaterniond(R_RW) * q;
    r.linear = R_RW * (r.linear - reference->v_W);
    r.angular = R_RW * (r.angular - reference->w_W);
  }
  r.position += config_.xyz_offsets;
  r.orientation = (q_offset_ * q).normalized();
  if (config_.gaussian_noise > 0.0) {
    std::normal_distribution<double> gauss(0.0, config_.gaussian_noise);
    for (int i = 0; i < 3; ++i) r.linear[i] += gauss(rng_);
    for (int i = 0; i < 3; ++i) r.angular[i] += gauss(rng_);
  }
  return r;
}

}  // namespace tianracer_sim
