#include "tianracer_control/controllers/diff_drive_controller.h"

#include <cmath>
#include <sstream>

#include <urdf_model/model.h>

namespace tianracer_control {

namespace {

// An outbox nobody empties (a host without ROS) keeps the latest samples only.
constexpr std::size_t kOutboxLimit = 100;
template <class T>
void post(std::vector<T>* box, const T& sample) {
  if (box->size() >= kOutboxLimit) box->erase(box->begin());
  box->push_back(sample);
}

std::string str(double x) {
  std::ostringstream os;
  os << x;
  return os.str();
}

// setOdomPubFields(): a list of 6 numbers (upstream asserts it; absent gives zeros).
std::array<double, 6> readCovariance(ControllerParams& params, const std::string& key) {
  std::array<double, 6> out{};
  const ParamValue* v = params.value(key);
  if (!v) return out;
  const bool list = v->kind() == ParamValue::Kind::kList && v->items().size() == 6;
  for (std::size_t i = 0; list && i < 6; ++i) {
    const ParamValue& item = v->items()[i];
    if (item.kind() == ParamValue::Kind::kDouble) {
      out[i] = item.asDouble();
    } else if (item.kind() == ParamValue::Kind::kInt) {
      out[i] = item.asInt();
    } else {
      throw ControllerError(params.prefix() + key + " must be a list of 6 numbers, item " +
                            std::to_string(i) + " is " + item.typeName());
    }
  }
  if (!list) {
    throw ControllerError(params.prefix() + key + " must be a list of 6 numbers, got " +
                          (v->kind() == ParamValue::Kind::kList
                               ? "a list of " + std::to_string(v->items().size())
                               : std::string(v->typeName())));
  }
  return out;
}

double positive(ControllerParams& params, const std::string& key, double fallback,
                bool zero_ok = false) {
  const double x = params.number(key).value_or(fallback);
  if (!std::isfinite(x) || x < 0.0 || (x == 0.0 && !zero_ok)) {
    throw ControllerError(params.prefix() + key + " must be a " +
                          (zero_ok ? "non-negative" : "positive") + " number, got " + str(x));
  }
  return x;
}

}  // namespace

std::vector<std::string> readWheelNames(ControllerParams& params, const std::string& key) {
  const std::string pre = params.prefix();
  const ParamValue* v = params.value(key);
  if (!v) throw ControllerError(pre + "Couldn't retrieve wheel param '" + key + "'.");
  if (v->kind() == ParamValue::Kind::kString) return {v->asString()};
  if (v->kind() != ParamValue::Kind::kList) {
    throw ControllerError(pre + "Wheel param '" + key +
                          "' is neither a list of strings nor a string.");
  }
  if (v->items().empty()) {
    throw ControllerError(pre + "Wheel param '" + key + "' is an empty list");
  }
  std::vector<std::string> names;
  for (std::size_t i = 0; i < v->items().size(); ++i) {
    if (v->items()[i].kind() != ParamValue::Kind::kString) {
      throw ControllerError(pre + "Wheel param '" + key + "' #" + std::to_string(i) +
                            " isn't a string.");
    }
    names.push_back(v->items()[i].asString());
  }
  return names;
}

double wheelRadiusFromUrdf(const urdf::ModelInterface& urdf, const std::string& joint,
                           const std::string& pre) {
  const urdf::JointConstSharedPtr j = urdf.getJoint(joint);
  const urdf::LinkConstSharedPtr link = j ? urdf.getLink(j->child_link_name) : nullptr;
  const std::string fail = "\n" + pre + "Couldn't retrieve " + joint + " wheel radius";
  if (!link) throw ControllerError(pre + "Link pointer is null." + fail);
  if (!link->collision) {
    throw ControllerError(pre + "Link " + link->name +
                          " does not have collision description. Add collision description for "
                          "link to urdf." + fail);
  }
  if (!link->collision->geometry) {
    throw ControllerError(pre + "Link " + link->name +
                          " does not have collision geometry description. Add collision geometry "
                          "description for link to urdf." + fail);
  }
  const urdf::Geometry& g = *link->collision->geometry;
  if (g.type == urdf::Geometry::CYLINDER) return static_cast<const urdf::Cylinder&>(g).radius;
  if (g.type == urdf::Geometry::SPHERE) return static_cast<const urdf::Sphere&>(g).radius;
  throw ControllerError(pre + "Wheel link " + link->name + " is NOT modeled as a cylinder or sphere!" +
                        fail);
}

std::unique_ptr<Controller> DiffDriveController::create(ControllerContext& context) {
  ControllerParams& params = context.params;
  const std::string pre = params.prefix();
  Params p;
  p.left_wheels = readWheelNames(params, "left_wheel");
  p.right_wheels = readWheelNames(params, "right_wheel");
  if (p.left_wheels.size() != p.right_wheels.size()) {
    throw ControllerError(pre + "#left wheels (" + std::to_string(p.left_wheels.size()) +
                          ") != #right wheels (" + std::to_string(p.right_wheels.size()) + ").");
  }
  p.publish_rate = positive(params, "publish_rate", p.publish_rate, true);
  p.open_loop = params.boolean("open_loop").value_or(p.open_loop);
  p.wheel_separation_multiplier =
      positive(params, "wheel_separation_multiplier", p.wheel_separation_multiplier);
  if (params.value("wheel_radius_multiplier")) {
    p.left_wheel_radius_multiplier = p.right_wheel_radius_multiplier =
        positive(params, "wheel_radius_multiplier", 1.0);
  } else {
    p.left_wheel_radius_multiplier = positive(params, "left_wheel_radius_multiplier", 1.0);
    p.right_wheel_radius_multiplier = positive(params, "right_wheel_radius_multiplier", 1.0);
  }
  const double window = params.number("velocity_rolling_window_size").value_or(10);
  if (!(window >= 1.0) || window != std::floor(window) || window > 1e6) {
    throw ControllerError(pre + "velocity_rolling_window_size must be a positive integer, got " +
                          str(window));
  }
  p.velocity_rolling_window_size = static_cast<int>(window);
  p.cmd_vel_timeout = params.number("cmd_vel_timeout").value_or(p.cmd_vel_timeout);
  if (std::isnan(p.cmd_vel_timeout)) {
    throw ControllerError(pre + "cmd_vel_timeout must be a number, got nan");
  }
  p.allow_multiple_cmd_vel_publishers =
      params.boolean("allow_multiple_cmd_vel_publishers").value_or(true);
  p.base_frame_id = params.text("base_frame_id").value_or(p.base_frame_id);
  p.odom_frame_id = params.text("odom_frame_id").value_or(p.odom_frame_id);
  p.enable_odom_tf = params.boolean("enable_odom_tf").value_or(p.enable_odom_tf);
  p.limiter_lin = SpeedLimiter::read(params, "linear/x");
  p.limiter_ang = SpeedLimiter::read(params, "angular/z");
  p.publish_cmd = params.boolean("publish_cmd").value_or(false);
  p.publish_wheel_joint_controller_state =
      params.boolean("publish_wheel_joint_controller_state").value_or(false);
  if (p.publish_wheel_joint_controller_state && context.warn) {
    context.warn(pre + "publish_wheel_joint_controller_state: not published here "
                 "(control_msgs/JointTrajectoryControllerState is not available)");
  }

  // setOdomParamsFromUrdf(): what is not given comes from the first wheel of each side.
  const std::optional<double> separation = params.number("wheel_separation");
  const std::optional<double> radius = params.number("wheel_radius");
  if (!separation || !radius) {
    const urdf::ModelInterface* urdf = context.robot_description;
    if (!urdf) {
      throw ControllerError(pre + "Robot description couldn't be retrieved from param server.");
    }
    const urdf::JointConstSharedPtr left = urdf->getJoint(p.left_wheels[0]);
    const urdf::JointConstSharedPtr right = urdf->getJoint(p.right_wheels[0]);
    for (const auto& [joint, name] : {std::pair(left, p.left_wheels[0]),
                                      std::pair(right, p.right_wheels[0])}) {
      if (!joint) {
        throw ControllerError(pre + name + " couldn't be retrieved from model description");
      }
    }
    if (!separation) {
      // The distance between the two joints' origins, each in its parent link's frame.
      const urdf::Vector3& a = left->parent_to_joint_origin_transform.position;
      const urdf::Vector3& b = right->parent_to_joint_origin_transform.position;
      p.wheel_separation = std::sqrt((a.x - b.x) * (a.x - b.x) + (a.y - b.y) * (a.y - b.y) +
                                     (a.z - b.z) * (a.z - b.z));
    }
    if (!radius) p.wheel_radius = wheelRadiusFromUrdf(*urdf, p.left_wheels[0], pre);
  }
  if (separation) p.wheel_separation = *separation;
  if (radius) p.wheel_radius = *radius;
  if (!(p.wheel_separation > 0.0) || !std::isfinite(p.wheel_separation)) {
    throw ControllerError(pre + "wheel_separation must be positive, got " +
                          str(p.wheel_separation) +
                          (separation ? "" : " (from the wheel joints' origins in the URDF)"));
  }
  if (!(p.wheel_radius > 0.0) || !std::isfinite(p.wheel_radius)) {
    throw ControllerError(pre + "wheel_radius must be positive, got " + str(p.wheel_radius));
  }
  p.pose_covariance_diagonal = readCovariance(params, "pose_covariance_diagonal");
  p.twist_covariance_diagonal = readCovariance(params, "twist_covariance_diagonal");

  std::vector<JointHandle*> left, right;
  for (std::size_t i = 0; i < p.left_wheels.size(); ++i) {
    left.push_back(findJoint(context, p.left_wheels[i], JointHandle::Interface::kVelocity));
    right.push_back(findJoint(context, p.right_wheels[i], JointHandle::Interface::kVelocity));
  }
  return std::make_unique<DiffDriveController>(params.name(), std::move(p), std::move(left),
                                               std::move(right));
}

DiffDriveController::DiffDriveController(std::string name, Params params,
                                         std::vector<JointHandle*> left,
                                         std::vector<JointHandle*> right)
    : Controller(std::move(name), kType),
      params_(std::move(params)),
      left_(std::move(left)),
      right_(std::move(right)),
      odometry_(static_cast<std::size_t>(params_.velocity_rolling_window_size)) {
  odometry_.setWheelParams(wheelSeparation(), leftWheelRadius(), rightWheelRadius());
}

std::vector<const JointHandle*> DiffDriveController::claimedJoints() const {
  std::vector<const JointHandle*> out(left_.begin(), left_.end());
  out.insert(out.end(), right_.begin(), right_.end());
  return out;
}

void DiffDriveController::setWheels(double left, double right) {
  for (JointHandle* j : left_) j->command = left;
  for (JointHandle* j : right_) j->command = right;
}

void DiffDriveController::brake() { setWheels(0.0, 0.0); }

void DiffDriveController::starting(double time) {
  brake();
  last_publish_ = time;
  odometry_.init(time);
}

void DiffDriveController::reset() {
  command_ = Command();
  stamp_pending_ = false;
  last0_ = last1_ = Command();
  double left = 0.0, right = 0.0;
  for (std::size_t i = 0; i < left_.size(); ++i) {
    left += left_[i]->position / left_.size();
    right += right_[i]->position / right_.size();
  }
  odometry_.resetPose(left, right);
  odom_out_.clear();
  cmd_out_.clear();
}

bool DiffDriveController::setCommand(double linear, double angular) {
  if (!std::isfinite(linear) || !std::isfinite(angular)) return false;
  command_.lin = linear;
  command_.ang = angular;
  stamp_pending_ = true;
  return true;
}

void DiffDriveController::setDynamicParams(const DynamicParams& d) {
  params_.left_wheel_radius_multiplier = d.left_wheel_radius_multiplier;
  params_.right_wheel_radius_multiplier = d.right_wheel_radius_multiplier;
  params_.wheel_separation_multiplier = d.wheel_separation_multiplier;
  params_.publish_rate = d.publish_rate;
  params_.enable_odom_tf = d.enable_odom_tf;
}

DiffDriveController::DynamicParams DiffDriveController::dynamicParams() const {
  return {params_.left_wheel_radius_multiplier, params_.right_wheel_radius_multiplier,
          params_.wheel_separation_multiplier, params_.publish_rate, params_.enable_odom_tf};
}

void DiffDriveController::update(double dt) {
  const double time = now();
  if (stamp_pending_) {  // the command arrived since the last update: stamped now
    command_.stamp = time;
    stamp_pending_ = false;
  }
  const double ws = wheelSeparation(), lwr = leftWheelRadius(), rwr = rightWheelRadius();
  odometry_.setWheelParams(ws, lwr, rwr);

  if (params_.open_loop) {
    odometry_.updateOpenLoop(last0_.lin, last0_.ang, time);
  } else {
    double left = 0.0, right = 0.0;
    for (std::size_t i = 0; i < left_.size(); ++i) {
      const double lp = left_[i]->position, rp = right_[i]->position;
      if (std::isnan(lp) || std::isnan(rp)) return;
      left += lp;
      right += rp;
    }
    odometry_.update(left / left_.size(), right / right_.size(), time);
  }

  // publish_period = 1 / publish_rate (0: never).
  const double period = 1.0 / params_.publish_rate;
  if (last_publish_ + period < time) {
    last_publish_ += period;
    post(&odom_out_, {time, odometry_.x(), odometry_.y(), odometry_.heading(), odometry_.linear(),
                      odometry_.angular(), params_.enable_odom_tf});
  }

  Command cmd = command_;
  if (time - cmd.stamp > params_.cmd_vel_timeout) {
    cmd.lin = 0.0;
    cmd.ang = 0.0;
  }
  params_.limiter_lin.limit(cmd.lin, last0_.lin, last1_.lin, dt);
  params_.limiter_ang.limit(cmd.ang, last0_.ang, last1_.ang, dt);
  last1_ = last0_;
  last0_ = cmd;
  if (params_.publish_cmd) post(&cmd_out_, {time, cmd.lin, cmd.ang});

  setWheels((cmd.lin - cmd.ang * ws / 2.0) / lwr, (cmd.lin + cmd.ang * ws / 2.0) / rwr);
}

std::vector<DiffDriveController::OdomSample> DiffDriveController::takeOdom() {
  std::vector<OdomSample> out;
  out.swap(odom_out_);
  return out;
}

std::vector<DiffDriveController::CmdSample> DiffDriveController::takeCmdOut() {
  std::vector<CmdSample> out;
  out.swap(cmd_out_);
  return out;
}

}  // namespace tianracer_control
