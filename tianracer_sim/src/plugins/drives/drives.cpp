#include "tianracer_sim/plugins/drives/drives.h"

#include <cmath>

#include "tianracer_sim/common/text.h"
#include "tianracer_sim/common/xml_reader.h"
#include "tianracer_sim/model/plugin_reader.h"

namespace tianracer_sim {
namespace {

// Seconds between two sim times as Gazebo's common::Time (integer nanoseconds) gives them, so
// that "t - last > period" on a 1 ms grid is decided as upstream decides it.
double elapsed(double t, double last) { return std::round((t - last) * 1e9) / 1e9; }

constexpr double kUnknownVariance = 1000000000000.0;  // upstream's "not measured" (z, roll, pitch)

// gazebo_plugins' getParameter (gazebo_ros_utils.h): the value, or the default with a
// "missing" note in DriveConfig::defaulted. Values are read by the one PluginReader.
class ParamReader : public PluginReader {
 public:
  ParamReader(const PluginSpec& p, std::string what, const WarningSink& warn, DriveConfig* c)
      : PluginReader(p, std::move(what), warn), c_(c) {}

  std::string textOr(const std::string& key, const std::string& def, bool note = true) {
    if (const auto v = text(key)) return *v;
    if (note) c_->defaulted.push_back("missing <" + key + ">, defaults to \"" + def + "\"");
    return def;
  }

  double numberOr(const std::string& key, double def, bool note = true) {
    double v = def;
    if (!number(key, &v) && note)
      c_->defaulted.push_back("missing <" + key + ">, defaults to " + formatNumber(def));
    return v;
  }

  bool booleanOr(const std::string& key, bool def, bool note = true) {
    bool v = def;
    if (!boolean(key, &v) && note)
      c_->defaulted.push_back("missing <" + key + ">, defaults to " + (def ? "true" : "false"));
    return v;
  }

  void require(bool ok, const std::string& key, double v, const std::string& rule) const {
    if (!ok) fail("<" + key + "> " + formatNumber(v) + " " + rule);
  }

 private:
  DriveConfig* c_;
};

void covariances(double cx, double cy, double cyaw, std::array<double, 36>* cov) {
  cov->fill(0.0);
  (*cov)[0] = cx;
  (*cov)[7] = cy;
  (*cov)[14] = (*cov)[21] = (*cov)[28] = kUnknownVariance;
  (*cov)[35] = cyaw;
}

void parseDiffDrive(ParamReader& r, const std::string& model_name, DriveConfig* c) {
  // GazeboRos (gazebo_ros_utils.h): the model's name unless <robotNamespace> is given and not
  // empty; then readCommonParameter's <rosDebugLevel>.
  c->robot_namespace = model_name;
  r.robotNamespace(NamespaceRule::kEmptyIsModel, &c->robot_namespace);
  c->ros_debug_level = r.textOr("rosDebugLevel", "na");
  c->command_topic = r.textOr("commandTopic", "cmd_vel");
  c->odometry_topic = r.textOr("odometryTopic", "odom");
  c->odometry_frame = r.textOr("odometryFrame", "odom");
  c->robot_base_frame = r.textOr("robotBaseFrame", "base_footprint");
  c->publish_wheel_tf = r.booleanOr("publishWheelTF", false);
  c->publish_odom_tf = r.booleanOr("publishOdomTF", true);
  c->publish_wheel_joint_state = r.booleanOr("publishWheelJointState", false);
  c->wheel_separation = r.numberOr("wheelSeparation", 0.34);
  c->wheel_diameter = r.numberOr("wheelDiameter", 0.15);
  c->wheel_acceleration = r.numberOr("wheelAcceleration", 0.0);
  c->wheel_torque = r.numberOr("wheelTorque", 5.0);
  c->update_rate = r.numberOr("updateRate", 100.0);
  const std::string source = r.textOr("odometrySource", "world");
  if (source == "world") {
    c->odometry_source = OdomSource::kWorld;
  } else if (source == "encoder") {
    c->odometry_source = OdomSource::kEncoder;
  } else {
    r.fail("<odometrySource> '" + source + "' is neither encoder nor world");
  }
  c->joints = {r.textOr("leftJoint", "left_joint"), r.textOr("rightJoint", "right_joint")};
  c->publish_odometry = r.booleanOr("publishTf", true);
  r.require(c->wheel_acceleration >= 0.0, "wheelAcceleration", c->wheel_acceleration,
            "must be >= 0");
  covariances(0.00001, 0.00001, 0.001, &c->pose_covariance);
}

void parseSkidSteer(ParamReader& r, DriveConfig* c) {
  // Its own node handle: <robotNamespace> + "/", else "" (no model-name default).
  if (r.robotNamespace(NamespaceRule::kAsGiven, &c->robot_namespace) == NamespaceFrom::kGiven)
    c->robot_namespace += "/";
  c->publish_odom_tf = r.booleanOr("broadcastTF", false, /*note=*/false);  // upstream: ROS_INFO
  c->joints = {r.textOr("leftFrontJoint", "left_front_joint"),
               r.textOr("rightFrontJoint", "right_front_joint"),
               r.textOr("leftRearJoint", "left_rear_joint"),
               r.textOr("rightRearJoint", "right_rear_joint")};
  c->wheel_separation = r.numberOr("wheelSeparation", 0.4);
  c->wheel_diameter = r.numberOr("wheelDiameter", 0.15);
  c->wheel_torque = r.numberOr("torque", 5.0);
  c->command_topic = r.textOr("commandTopic", "cmd_vel");
  c->odometry_topic = r.textOr("odometryTopic", "odom");
  c->odometry_frame = r.textOr("odometryFrame", "odom");
  c->robot_base_frame = r.textOr("robotBaseFrame", "base_footprint");
  c->update_rate = r.numberOr("updateRate", 100.0);
  const double cx = r.numberOr("covariance_x", 0.0001);
  const double cy = r.numberOr("covariance_y", 0.0001);
  const double cyaw = r.numberOr("covariance_yaw", 0.01);
  covariances(cx, cy, cyaw, &c->pose_covariance);
  covariances(cx, cy, cyaw, &c->twist_covariance);
}

void parsePlanarMove(ParamReader& r, DriveConfig* c) {
  r.robotNamespace(NamespaceRule::kAsGiven, &c->robot_namespace);
  c->command_topic = r.textOr("commandTopic", "cmd_vel");
  c->odometry_topic = r.textOr("odometryTopic", "odom");
  c->odometry_frame = r.textOr("odometryFrame", "odom");
  c->robot_base_frame = r.textOr("robotBaseFrame", "base_footprint");
  c->update_rate = r.numberOr("odometryRate", 20.0);
  c->cmd_timeout = r.numberOr("cmdTimeout", -1.0);
  c->publish_odom_tf = true;
  covariances(0.00001, 0.00001, 0.001, &c->pose_covariance);
}

}  // namespace

DriveConfig parseDriveConfig(const SensorSpec& spec, const std::string& model_name,
                             const WarningSink& warn) {
  if (spec.plugins.size() != 1) throw SensorError("drive plugin '" + spec.name + "': expected one plugin");
  const PluginSpec& p = spec.plugins.front();
  DriveConfig c;
  c.name = spec.name;
  c.filename = baseName(p.filename);
  std::string kind_name;
  if (c.filename == "libgazebo_ros_diff_drive.so") {
    c.kind = DriveKind::kDiffDrive;
    kind_name = "diff_drive";
  } else if (c.filename == "libgazebo_ros_skid_steer_drive.so") {
    c.kind = DriveKind::kSkidSteer;
    kind_name = "skid_steer_drive";
  } else if (c.filename == "libgazebo_ros_planar_move.so") {
    c.kind = DriveKind::kPlanarMove;
    kind_name = "planar_move";
  } else {
    throw SensorError("plugin '" + spec.name + "' (" + p.filename + ") is not a drive plugin");
  }
  const std::string what = kind_name + " plugin '" + spec.name + "' of model '" + model_name + "'";
  ParamReader r(p, what, warn, &c);
  switch (c.kind) {
    case DriveKind::kDiffDrive: parseDiffDrive(r, model_name, &c); break;
    case DriveKind::kSkidSteer: parseSkidSteer(r, &c); break;
    case DriveKind::kPlanarMove: parsePlanarMove(r, &c); break;
  }
  if (c.drivesJoints()) {
    r.require(c.wheel_diameter > 0.0, "wheelDiameter", c.wheel_diameter,
              "must be > 0 (wheel rates are rim speeds / (wheelDiameter / 2))");
    r.require(c.wheel_separation > 0.0, "wheelSeparation", c.wheel_separation, "must be > 0");
    r.require(c.wheel_torque >= 0.0, c.kind == DriveKind::kSkidSteer ? "torque" : "wheelTorque",
              c.wheel_torque, "must be >= 0");
    r.require(c.update_rate >= 0.0, "updateRate", c.update_rate, "must be >= 0");
    for (const std::string& j : c.joints) {
      if (j.empty()) r.fail("a wheel joint's name is empty");
    }
  } else {
    r.require(c.update_rate >= 0.0, "odometryRate", c.update_rate, "must be >= 0");
  }
  // Read by no noetic plugin, written by many models: alwaysOn (old gazebo_ros), legacyMode
  // (melodic's diff drive); noetic ignores them as we do.
  r.ignore({"alwaysOn", "legacyMode"});
  r.finish();
  return c;
}

std::vector<SensorTopic> publishedTopics(const DriveConfig& c) {
  std::vector<SensorTopic> topics;
  const bool odometry = c.kind == DriveKind::kPlanarMove ? c.update_rate > 0.0 : c.publish_odometry;
  if (odometry) topics.push_back({c.odometryTopic(), "nav_msgs/Odometry", c.update_rate});
  if (c.publish_wheel_joint_state)
    topics.push_back({c.jointStatesTopic(), "sensor_msgs/JointState", c.update_rate});
  topics.push_back({c.commandTopic(), "geometry_msgs/Twist (subscribed)", 0.0});
  return topics;
}

WheelSpeeds wheelSpeeds(double v, double w, double separation) {
  return {v - w * separation / 2.0, v + w * separation / 2.0};
}

WheelSpeeds rampWheelSpeeds(const WheelSpeeds& target, const WheelSpeeds& current, double accel,
                            double dt, WheelSpeeds* issued) {
  if (accel == 0.0 || std::fabs(target.left - current.left) < 0.01 ||
      std::fabs(target.right - current.right) < 0.01) {
    return target;
  }
  const double step = accel * dt;
  issued->left += std::clamp(target.left - current.left, -step, step);
  issued->right += std::clamp(target.right - current.right, -step, step);
  return *issued;
}

void EncoderOdometry::update(double omega_left, double omega_right, double radius,
                             double separation, double dt) {
  const double sl = omega_left * radius * dt;
  const double sr = omega_right * radius * dt;
  const double ssum = sl + sr, sdiff = sr - sl;
  const double heading = theta_ + sdiff / (2.0 * separation);
  x_ += ssum / 2.0 * std::cos(heading);
  y_ += ssum / 2.0 * std::sin(heading);
  theta_ += sdiff / separation;
  if (dt > 0.0) {
    v_ = ssum / 2.0 / dt;
    w_ = sdiff / separation / dt;
  }
}

double yawOf(const Eigen::Quaterniond& q) {
  // ignition::math::Quaternion::Euler()'s z component.
  return std::atan2(2.0 * (q.w() * q.z() + q.x() * q.y()),
                    1.0 - 2.0 * (q.y() * q.y() + q.z() * q.z()));
}

void worldOdometry(const LinkState& model, bool with_z, DriveOdometry* odom) {
  const Eigen::Vector3d p = model.X_WL.translation();
  odom->position = Eigen::Vector3d(p.x(), p.y(), with_z ? p.z() : 0.0);
  odom->orientation = Eigen::Quaterniond(model.X_WL.rotation()).normalized();
  const double yaw = yawOf(odom->orientation);
  const double c = std::cos(yaw), s = std::sin(yaw);
  odom->linear = Eigen::Vector3d(c * model.v_W.x() + s * model.v_W.y(),
                                 c * model.v_W.y() - s * model.v_W.x(), 0.0);
  odom->angular = Eigen::Vector3d(0.0, 0.0, model.w_W.z());
  odom->X_OB = model.X_WL;
}

DriveCore::DriveCore(DriveConfig config) : config_(std::move(config)) {
  odom_.pose_covariance = config_.pose_covariance;
  odom_.twist_covariance = config_.twist_covariance;
  step_.wheel_omega.assign(config_.joints.size(), 0.0);
}

bool DriveCore::setCommand(double vx, double vy, double wz, double t) {
  if (!std::isfinite(vx) || !std::isfinite(vy) || !std::isfinite(wz)) return false;
  vx_ = vx;
  vy_ = config_.kind == DriveKind::kPlanarMove ? vy : 0.0;  // the drives read x and yaw only
  wz_ = wz;
  last_cmd_ = t;
  return true;
}

void DriveCore::restart(double t, const LinkState& model) {
  last_update_ = t;
  last_odom_ = t;
  last_cmd_ = t;
  last_pose_ = model;
  issued_ = WheelSpeeds();
  encoder_.reset();
  started_ = true;
}

const DriveCore::Step& DriveCore::update(double t, const LinkState& model,
                                         const std::vector<double>& omega) {
  if (!started_) restart(0.0, model);  // upstream loads with the world at 0
  Step& s = step_;
  s.due = s.set_wheels = s.set_twist = false;
  const double r = config_.wheel_diameter / 2.0;
  const double period = config_.update_rate > 0.0 ? 1.0 / config_.update_rate : 0.0;

  if (config_.kind == DriveKind::kPlanarMove) {
    // UpdateChild: expire the command, set the velocity every step; odometry at its rate,
    // its schedule restarting from each publication.
    if (config_.cmd_timeout >= 0.0 && elapsed(t, last_cmd_) > config_.cmd_timeout) vx_ = vy_ = wz_ = 0.0;
    const double yaw = yawOf(Eigen::Quaterniond(model.X_WL.rotation()));
    const double c = std::cos(yaw), sn = std::sin(yaw);
    s.set_twist = true;
    s.linear_W = Eigen::Vector3d(vx_ * c - vy_ * sn, vy_ * c + vx_ * sn, 0.0);
    s.angular_W = Eigen::Vector3d(0.0, 0.0, wz_);
    if (config_.update_rate > 0.0 && elapsed(t, last_update_) > 1.0 / config_.update_rate) {
      const double dt = t - last_update_;
      DriveOdometry& o = odom_;
      const Eigen::Vector3d p = model.X_WL.translation();
      const Eigen::Vector3d p0 = last_pose_.X_WL.translation();
      o.position = Eigen::Vector3d(p.x(), p.y(), 0.0);
      o.orientation = Eigen::Quaterniond(model.X_WL.rotation()).normalized();
      const double vx = (p.x() - p0.x()) / dt, vy = (p.y() - p0.y()) / dt;
      if (wz_ > M_PI / dt) {
        o.angular.z() = wz_;  // faster than the differences can tell
      } else {
        const double last_yaw = yawOf(Eigen::Quaterniond(last_pose_.X_WL.rotation()));
        double yaw_now = yaw;
        while (yaw_now < last_yaw - M_PI) yaw_now += 2.0 * M_PI;
        while (yaw_now > last_yaw + M_PI) yaw_now -= 2.0 * M_PI;
        o.angular.z() = (yaw_now - last_yaw) / dt;
      }
      o.linear = Eigen::Vector3d(c * vx + sn * vy, c * vy - sn * vx, 0.0);
      o.X_OB = model.X_WL;
      last_pose_ = model;
      last_update_ = t;
      s.due = true;
    }
    return s;
  }

  const bool diff = config_.kind == DriveKind::kDiffDrive;
  const bool encoder = diff && config_.odometry_source == OdomSource::kEncoder;
  if (encoder) {
    encoder_.update(omega[0], omega[1], r, config_.wheel_separation, t - last_odom_);
    last_odom_ = t;
  }
  if (!(elapsed(t, last_update_) > period)) return s;
  s.due = true;
  if (encoder) {
    odom_.position = Eigen::Vector3d(encoder_.x(), encoder_.y(), 0.0);
    odom_.orientation = Eigen::Quaterniond(Eigen::AngleAxisd(encoder_.theta(), Eigen::Vector3d::UnitZ()));
    odom_.linear = Eigen::Vector3d(encoder_.v(), 0.0, 0.0);
    odom_.angular = Eigen::Vector3d(0.0, 0.0, encoder_.w());
    odom_.X_OB = Eigen::Translation3d(odom_.position) * odom_.orientation;
  } else {
    worldOdometry(model, diff, &odom_);
  }
  const WheelSpeeds target = wheelSpeeds(vx_, wz_, config_.wheel_separation);
  s.set_wheels = true;
  if (diff) {
    const WheelSpeeds current{omega[0] * r, omega[1] * r};
    const WheelSpeeds cmd = rampWheelSpeeds(target, current, config_.wheel_acceleration,
                                            t - last_update_, &issued_);
    s.wheel_omega[0] = cmd.left / r;
    s.wheel_omega[1] = cmd.right / r;
  } else {
    s.wheel_omega = {target.left / r, target.right / r, target.left / r, target.right / r};
  }
  last_update_ += period;
  return s;
}

}  // namespace tianracer_sim
