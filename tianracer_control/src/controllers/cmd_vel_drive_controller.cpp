#include "tianracer_control/controllers/cmd_vel_drive_controller.h"

#include <cmath>
#include <sstream>

#include <urdf_model/model.h>

namespace tianracer_control {

namespace {

// setOdomPubFields(): a list of 6 numbers (upstream asserts it; absent gives zeros).
std::array<double, 6> readCovariance(ControllerParams& params, const std::string& key) {
  std::array<double, 6> out{};
  const ParamValue* v = params.value(key);
  if (!v) return out;
  if (v->kind() != ParamValue::Kind::kList || v->items().size() != 6) {
    throw ControllerError(params.prefix() + key + " must be a list of 6 numbers, got " +
                          (v->kind() == ParamValue::Kind::kList
                               ? "a list of " + std::to_string(v->items().size())
                               : std::string(v->typeName())));
  }
  for (std::size_t i = 0; i < 6; ++i) {
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
  return out;
}

}  // namespace

CmdVelDriveController::Common CmdVelDriveController::readCommon(ControllerParams& params) {
  const std::string pre = params.prefix();
  Common c;
  c.publish_rate = params.number("publish_rate").value_or(c.publish_rate);
  if (!(c.publish_rate >= 0.0) || !std::isfinite(c.publish_rate)) {
    throw ControllerError(pre + "publish_rate must be a non-negative number, got " +
                          numberText(c.publish_rate));
  }
  c.open_loop = params.boolean("open_loop").value_or(c.open_loop);
  const double window = params.number("velocity_rolling_window_size").value_or(10);
  if (!(window >= 1.0) || window != std::floor(window) || window > 1e6) {
    throw ControllerError(pre + "velocity_rolling_window_size must be a positive integer, got " +
                          numberText(window));
  }
  c.velocity_rolling_window_size = static_cast<int>(window);
  c.cmd_vel_timeout = params.number("cmd_vel_timeout").value_or(c.cmd_vel_timeout);
  if (std::isnan(c.cmd_vel_timeout)) {
    throw ControllerError(pre + "cmd_vel_timeout must be a number, got nan");
  }
  c.allow_multiple_cmd_vel_publishers =
      params.boolean("allow_multiple_cmd_vel_publishers").value_or(true);
  c.base_frame_id = params.text("base_frame_id").value_or(c.base_frame_id);
  c.odom_frame_id = params.text("odom_frame_id").value_or(c.odom_frame_id);
  c.enable_odom_tf = params.boolean("enable_odom_tf").value_or(c.enable_odom_tf);
  c.limiter_lin = SpeedLimiter::read(params, "linear/x");
  c.limiter_ang = SpeedLimiter::read(params, "angular/z");
  c.pose_covariance_diagonal = readCovariance(params, "pose_covariance_diagonal");
  c.twist_covariance_diagonal = readCovariance(params, "twist_covariance_diagonal");
  return c;
}

double wheelRadiusFromUrdf(const urdf::ModelInterface& urdf, const std::string& joint,
                           const std::string& pre, bool sphere_ok) {
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
  if (g.type == urdf::Geometry::SPHERE && sphere_ok) {
    return static_cast<const urdf::Sphere&>(g).radius;
  }
  throw ControllerError(pre + "Wheel link " + link->name + " is NOT modeled as a cylinder" +
                        (sphere_ok ? " or sphere!" : "!") + fail);
}

CmdVelDriveController::CmdVelDriveController(std::string name, std::string type, Common common)
    : Controller(std::move(name), std::move(type)),
      common_(std::move(common)),
      odometry_(static_cast<std::size_t>(common_.velocity_rolling_window_size)) {}

void CmdVelDriveController::starting(double time) {
  brake();
  last_publish_ = time;
  odometry_.init(time);
}

void CmdVelDriveController::reset() {
  command_ = Command();
  stamp_pending_ = false;
  last0_ = last1_ = Command();
  resetOdometry();
  odom_out_.clear();
  cmd_out_.clear();
}

bool CmdVelDriveController::setCommand(double linear, double angular) {
  if (!std::isfinite(linear) || !std::isfinite(angular)) return false;
  command_.lin = linear;
  command_.ang = angular;
  stamp_pending_ = true;
  return true;
}

void CmdVelDriveController::update(double dt) {
  const double time = now();
  if (stamp_pending_) {  // the command arrived since the last update: stamped now
    command_.stamp = time;
    stamp_pending_ = false;
  }
  if (common_.open_loop) {
    odometry_.updateOpenLoop(last0_.lin, last0_.ang, time);
  } else if (!updateOdometry(time)) {
    return;
  }
  // publish_period = 1 / publish_rate (0: never).
  const double period = 1.0 / common_.publish_rate;
  if (last_publish_ + period < time) {
    last_publish_ += period;
    odom_out_.post({time, odometry_.x(), odometry_.y(), odometry_.heading(), odometry_.linear(),
                     odometry_.angular(), common_.enable_odom_tf});
  }
  Command cmd = command_;
  if (time - cmd.stamp > common_.cmd_vel_timeout) {
    cmd.lin = 0.0;
    cmd.ang = 0.0;
  }
  common_.limiter_lin.limit(cmd.lin, last0_.lin, last1_.lin, dt);
  common_.limiter_ang.limit(cmd.ang, last0_.ang, last1_.ang, dt);
  last1_ = last0_;
  last0_ = cmd;
  if (common_.publish_cmd) cmd_out_.post({time, cmd.lin, cmd.ang});
  update_dt_ = dt;
  drive(cmd.lin, cmd.ang);
}

std::vector<CmdVelDriveController::OdomSample> CmdVelDriveController::takeOdom() {
  return odom_out_.take();
}

std::vector<CmdVelDriveController::CmdSample> CmdVelDriveController::takeCmdOut() {
  return cmd_out_.take();
}

}  // namespace tianracer_control
