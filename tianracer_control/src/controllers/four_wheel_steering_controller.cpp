#include "tianracer_control/controllers/four_wheel_steering_controller.h"

#include <algorithm>
#include <cmath>
#include <sstream>

#include <urdf_model/model.h>

#include "tianracer_control/controllers/diff_drive_controller.h"

namespace tianracer_control {

namespace {

// urdf_geometry_parser's getTransformVector(): the joint's origin plus its ancestors' origins up
// to `base_link` (positions only, as upstream sums them).
urdf::Vector3 transformVector(const urdf::ModelInterface& urdf, const std::string& joint_name,
                              const std::string& base_link, const std::string& pre) {
  urdf::JointConstSharedPtr joint = urdf.getJoint(joint_name);
  if (!joint) throw ControllerError(pre + joint_name + " couldn't be retrieved from model description");
  urdf::Vector3 v = joint->parent_to_joint_origin_transform.position;
  while (joint->parent_link_name != base_link) {
    const urdf::LinkConstSharedPtr parent = urdf.getLink(joint->parent_link_name);
    if (!parent || !parent->parent_joint) {
      throw ControllerError(pre + joint->parent_link_name +
                            " couldn't be retrieved from model description or his parent joint");
    }
    joint = parent->parent_joint;
    const urdf::Vector3& p = joint->parent_to_joint_origin_transform.position;
    v = urdf::Vector3(v.x + p.x, v.y + p.y, v.z + p.z);
  }
  return v;
}

// getDistanceBetweenJoints(): the distance in the base's x-y plane.
double distanceBetweenJoints(const urdf::ModelInterface& urdf, const std::string& a, const std::string& b,
                             const std::string& base_link, const std::string& pre) {
  const urdf::Vector3 va = transformVector(urdf, a, base_link, pre), vb = transformVector(urdf, b, base_link, pre);
  return std::hypot(va.x - vb.x, va.y - vb.y);
}

// Two names per axle (left, right), as init() checks them.
std::array<std::string, 2> axle(const std::vector<std::string>& names, const std::string& what,
                                const std::string& pre) {
  if (names.size() != 2) {
    throw ControllerError(pre + "#two " + what + " by axle (left and right) is needed; now : " +
                          std::to_string(names.size()) + " .");
  }
  return {names[0], names[1]};
}

// atan(2 tan(l) tan(r) / (tan(l) + tan(r))): the virtual angle of an axle from its two wheels'.
double virtualAngle(double left, double right) {
  if (!(std::fabs(left) > 0.001 || std::fabs(right) > 0.001)) return 0.0;
  return std::atan(2 * std::tan(left) * std::tan(right) / (std::tan(left) + std::tan(right)));
}

}  // namespace

void FourWheelSteeringOdometry::setWindow(std::size_t window) {
  window_ = window;
  accel_ = RollingMean(window);
  jerk_ = RollingMean(window);
  front_steer_vel_ = RollingMean(window);
  rear_steer_vel_ = RollingMean(window);
}

void FourWheelSteeringOdometry::setWheelParams(double steering_track, double wheel_steering_y_offset,
                                               double wheel_radius, double wheel_base) {
  steering_track_ = steering_track;
  wheel_steering_y_offset_ = wheel_steering_y_offset;
  wheel_radius_ = wheel_radius;
  wheel_base_ = wheel_base;
}

void FourWheelSteeringOdometry::init(double time) {
  setWindow(window_);
  last_time_ = time;
}

// odometry.cpp, update(), term for term (the front speed's norm takes the raw wheel speeds, the
// rear's the offset-corrected ones, as upstream writes them).
bool FourWheelSteeringOdometry::update(double fl_speed, double fr_speed, double rl_speed, double rr_speed,
                                       double front_steering, double rear_steering, double time) {
  const double st = steering_track_, b = wheel_base_, off = wheel_steering_y_offset_;
  // One axle: its yaw-rate factor (tmp) and its linear speed. The norm takes the raw wheel speeds
  // at the front and the offset-corrected ones at the rear, as upstream writes them.
  struct Axle {
    double tmp, linear_speed;
  };
  const auto axle = [&](double l_speed, double r_speed, double steering, bool raw_norm) {
    const double tmp = std::cos(steering) * (std::tan(front_steering) - std::tan(rear_steering)) / b;
    const double left_tmp = tmp / std::sqrt(1 - st * tmp * std::cos(steering) + std::pow(st * tmp / 2, 2));
    const double right_tmp = tmp / std::sqrt(1 + st * tmp * std::cos(steering) + std::pow(st * tmp / 2, 2));
    const double l_tmp = l_speed * (1 / (1 - off * left_tmp)), r_tmp = r_speed * (1 / (1 - off * right_tmp));
    const double nl = raw_norm ? l_speed : l_tmp, nr = raw_norm ? r_speed : r_tmp;
    return Axle{tmp, wheel_radius_ * std::copysign(1.0, l_tmp + r_tmp) *
                         std::sqrt((nl * nl + nr * nr) / (2 + std::pow(st * tmp, 2) / 2.0))};
  };
  const Axle front = axle(fl_speed, fr_speed, front_steering, true);
  const Axle rear = axle(rl_speed, rr_speed, rear_steering, false);
  const double front_tmp = front.tmp, rear_tmp = rear.tmp;
  const double front_linear_speed = front.linear_speed, rear_linear_speed = rear.linear_speed;

  angular_ = (front_linear_speed * front_tmp + rear_linear_speed * rear_tmp) / 2.0;
  linear_x_ = (front_linear_speed * std::cos(front_steering) + rear_linear_speed * std::cos(rear_steering)) / 2.0;
  linear_y_ = (front_linear_speed * std::sin(front_steering) - b * angular_ / 2.0 +
               rear_linear_speed * std::sin(rear_steering) + b * angular_ / 2.0) /
              2.0;
  linear_ = std::copysign(1.0, rear_linear_speed) * std::sqrt(std::pow(linear_x_, 2) + std::pow(linear_y_, 2));

  const double dt = time - last_time_;
  if (dt < 0.0001) return false;  // too small an interval to integrate
  last_time_ = time;
  // integrateXY()
  const double dx = linear_x_ * dt, dy = linear_y_ * dt;
  x_ += dx * std::cos(heading_) - dy * std::sin(heading_);
  y_ += dx * std::sin(heading_) + dy * std::cos(heading_);
  heading_ += angular_ * dt;

  accel_.add((linear_vel_prev_ - linear_) / dt);
  linear_vel_prev_ = linear_;
  jerk_.add((linear_accel_prev_ - accel_.mean()) / dt);
  linear_accel_prev_ = accel_.mean();
  front_steer_vel_.add((front_steer_prev_ - front_steering) / dt);
  front_steer_prev_ = front_steering;
  rear_steer_vel_.add((rear_steer_prev_ - rear_steering) / dt);
  rear_steer_prev_ = rear_steering;
  return true;
}

std::unique_ptr<Controller> FourWheelSteeringController::create(ControllerContext& context) {
  ControllerParams& params = context.params;
  const std::string pre = params.prefix();
  const std::vector<std::string> front = readWheelNames(params, "front_wheel");
  const std::vector<std::string> rear = readWheelNames(params, "rear_wheel");
  if (front.size() != rear.size()) {
    throw ControllerError(pre + "#front wheels (" + std::to_string(front.size()) + ") != #rear wheels (" +
                          std::to_string(rear.size()) + ").");
  }
  Params p;
  p.front_wheels = axle(front, "wheels", pre);
  p.rear_wheels = axle(rear, "wheels", pre);
  const std::vector<std::string> front_steer = readWheelNames(params, "front_steering");
  const std::vector<std::string> rear_steer = readWheelNames(params, "rear_steering");
  if (front_steer.size() != rear_steer.size()) {
    throw ControllerError(pre + "#left steerings (" + std::to_string(front_steer.size()) +
                          ") != #right steerings (" + std::to_string(rear_steer.size()) + ").");
  }
  p.front_steering = axle(front_steer, "steering", pre);
  p.rear_steering = axle(rear_steer, "steering", pre);

  CmdVelDriveController::Common common = CmdVelDriveController::readCommon(params);
  // Its own speed_limiter.h has no jerk limits.
  common.limiter_lin.has_jerk_limits = common.limiter_ang.has_jerk_limits = false;

  const std::optional<double> track = params.number("track");
  const std::optional<double> radius = params.number("wheel_radius");
  const std::optional<double> base = params.number("wheel_base");
  const urdf::ModelInterface* urdf = context.robot_description;
  if (!urdf) throw ControllerError(pre + "Robot descripion couldn't be retrieved from param server.");
  const std::string& base_link = common.base_frame_id;
  p.track = track ? *track : distanceBetweenJoints(*urdf, p.front_wheels[0], p.front_wheels[1], base_link, pre);
  p.wheel_steering_y_offset = distanceBetweenJoints(*urdf, p.front_steering[0], p.front_wheels[0], base_link, pre);
  p.wheel_radius = radius ? *radius : wheelRadiusFromUrdf(*urdf, p.front_wheels[0], pre, false);
  p.wheel_base = base ? *base : distanceBetweenJoints(*urdf, p.front_wheels[0], p.rear_wheels[0], base_link, pre);
  for (const auto& [value, key] : {std::pair(p.track, "track"), std::pair(p.wheel_radius, "wheel_radius"),
                                   std::pair(p.wheel_base, "wheel_base")}) {
    if (!(value > 0.0) || !std::isfinite(value)) {
      throw ControllerError(pre + key + " must be positive, got " + numberText(value));
    }
  }

  std::array<JointHandle*, 4> wheels{}, steering{};
  const std::array<std::string, 4> wheel_names{p.front_wheels[0], p.front_wheels[1], p.rear_wheels[0],
                                               p.rear_wheels[1]};
  const std::array<std::string, 4> steer_names{p.front_steering[0], p.front_steering[1], p.rear_steering[0],
                                               p.rear_steering[1]};
  for (int i = 0; i < 4; ++i) {
    wheels[i] = findJoint(context, wheel_names[i], JointHandle::Interface::kVelocity);
    steering[i] = findJoint(context, steer_names[i], JointHandle::Interface::kPosition);
  }
  return std::make_unique<FourWheelSteeringController>(params.name(), std::move(common), std::move(p),
                                                       wheels, steering);
}

FourWheelSteeringController::FourWheelSteeringController(std::string name, CmdVelDriveController::Common common,
                                                         Params params, std::array<JointHandle*, 4> wheels,
                                                         std::array<JointHandle*, 4> steering)
    : Controller(std::move(name), kType),
      common_(std::move(common)),
      params_(std::move(params)),
      wheels_(wheels),
      steering_(steering),
      odometry_(static_cast<std::size_t>(common_.velocity_rolling_window_size)) {
  odometry_.setWheelParams(params_.track - 2 * params_.wheel_steering_y_offset, params_.wheel_steering_y_offset,
                           params_.wheel_radius, params_.wheel_base);
}

std::vector<const JointHandle*> FourWheelSteeringController::claimedJoints() const {
  std::vector<const JointHandle*> out(wheels_.begin(), wheels_.end());
  out.insert(out.end(), steering_.begin(), steering_.end());
  return out;
}

void FourWheelSteeringController::brake() {
  for (JointHandle* j : wheels_) j->command = 0.0;
  for (JointHandle* j : steering_) j->command = 0.0;
}

void FourWheelSteeringController::starting(double time) {
  brake();
  last_publish_ = time;
  odometry_.init(time);
}

void FourWheelSteeringController::reset() {
  twist_ = Twist();
  four_ws_ = FourWs();
  twist_pending_ = four_ws_pending_ = false;
  last0_ = last1_ = Twist();
  odometry_.resetPose();
  odom_out_.clear();
}

bool FourWheelSteeringController::setTwist(double linear_x, double linear_y, double angular) {
  if (std::isnan(angular) || std::isnan(linear_x)) return false;  // cmdVelCallback: NaN ignored
  twist_.lin_x = linear_x;
  twist_.lin_y = linear_y;
  twist_.ang = angular;
  twist_pending_ = true;
  return true;
}

bool FourWheelSteeringController::setFourWheelSteering(double front_steering, double rear_steering, double speed) {
  if (std::isnan(front_steering) || std::isnan(rear_steering) || std::isnan(speed)) return false;
  four_ws_.front_steering = front_steering;
  four_ws_.rear_steering = rear_steering;
  four_ws_.lin = speed;
  four_ws_pending_ = true;
  return true;
}

void FourWheelSteeringController::update(double dt) {
  const double time = now();
  // A command is stamped with the time of the first update after it arrived (upstream: the
  // callback's ros::Time::now()).
  if (twist_pending_) twist_.stamp = time;
  if (four_ws_pending_) four_ws_.stamp = time;
  twist_pending_ = four_ws_pending_ = false;
  updateOdometry(time);
  updateCommand(time, dt);
}

void FourWheelSteeringController::updateOdometry(double time) {
  double speed[4], angle[4];
  for (int i = 0; i < 4; ++i) {
    speed[i] = wheels_[i]->velocity;
    angle[i] = steering_[i]->position;
  }
  for (int i = 0; i < 4; ++i) {
    if (std::isnan(speed[i]) || std::isnan(angle[i])) return;
  }
  const double front = virtualAngle(angle[0], angle[1]), rear = virtualAngle(angle[2], angle[3]);
  odometry_.update(speed[0], speed[1], speed[2], speed[3], front, rear, time);
  const double period = 1.0 / common_.publish_rate;
  if (!(last_publish_ + period < time)) return;
  last_publish_ += period;
  OdomSample s{time,
               odometry_.x(),
               odometry_.y(),
               odometry_.heading(),
               odometry_.linearX(),
               odometry_.linearY(),
               odometry_.angular(),
               common_.enable_odom_tf,
               odometry_.linear(),
               odometry_.linearAcceleration(),
               odometry_.linearJerk(),
               front,
               odometry_.frontSteerVel(),
               rear,
               odometry_.rearSteerVel()};
  odom_out_.post(s);
}

// updateCommand(), term for term.
void FourWheelSteeringController::updateCommand(double time, double cmd_dt) {
  Twist twist = twist_;
  FourWs four_ws = four_ws_;
  const bool use_twist = !(four_ws.stamp >= twist.stamp);
  const double age = time - (use_twist ? twist.stamp : four_ws.stamp);
  if (age > common_.cmd_vel_timeout) {  // brake
    twist.lin_x = twist.lin_y = twist.ang = 0.0;
    four_ws.lin = four_ws.front_steering = four_ws.rear_steering = 0.0;
  }
  const double r = params_.wheel_radius, b = params_.wheel_base, off = params_.wheel_steering_y_offset;
  const double st = params_.track - 2 * off;
  double vel_fl = 0, vel_fr = 0, vel_rl = 0, vel_rr = 0;
  double steer_fl = 0, steer_fr = 0, steer_rl = 0, steer_rr = 0;
  if (use_twist) {
    common_.limiter_lin.limit(twist.lin_x, last0_.lin_x, last1_.lin_x, cmd_dt);
    common_.limiter_ang.limit(twist.ang, last0_.ang, last1_.ang, cmd_dt);
    last1_ = last0_;
    last0_ = twist;
    const double v = twist.lin_x, w = twist.ang;
    if (std::fabs(v) > 0.001) {
      const double vel_steering_offset = (w * off) / r;
      const double sign = std::copysign(1.0, v);
      vel_fl = sign * std::hypot(v - w * st / 2, b * w / 2.0) / r - vel_steering_offset;
      vel_fr = sign * std::hypot(v + w * st / 2, b * w / 2.0) / r + vel_steering_offset;
      vel_rl = sign * std::hypot(v - w * st / 2, b * w / 2.0) / r - vel_steering_offset;
      vel_rr = sign * std::hypot(v + w * st / 2, b * w / 2.0) / r + vel_steering_offset;
    }
    if (std::fabs(2.0 * v) > std::fabs(w * st)) {
      steer_fl = std::atan(w * b / (2.0 * v - w * st));
      steer_fr = std::atan(w * b / (2.0 * v + w * st));
    } else if (std::fabs(v) > 0.001) {
      steer_fl = steer_fr = std::copysign(M_PI_2, w);
    }
    steer_rl = -steer_fl;
    steer_rr = -steer_fr;
  } else {
    common_.limiter_lin.limit(four_ws.lin, last0_.lin_x, last1_.lin_x, cmd_dt);
    last1_ = last0_;
    last0_.lin_x = four_ws.lin;
    four_ws.front_steering = std::clamp(four_ws.front_steering, -M_PI_2, M_PI_2);
    four_ws.rear_steering = std::clamp(four_ws.rear_steering, -M_PI_2, M_PI_2);
    const double tan_front = std::tan(four_ws.front_steering), tan_rear = std::tan(four_ws.rear_steering);
    const double steering_diff = st * (tan_front - tan_rear) / 2.0;
    if (std::fabs(b - std::fabs(steering_diff)) > 0.001) {
      steer_fl = std::atan(b * tan_front / (b - steering_diff));
      steer_fr = std::atan(b * tan_front / (b + steering_diff));
      steer_rl = std::atan(b * tan_rear / (b - steering_diff));
      steer_rr = std::atan(b * tan_rear / (b + steering_diff));
    }
    const double v = four_ws.lin;
    if (std::fabs(v) > 0.001) {
      // The distances from each axle to the projection of the centre of rotation on the wheelbase.
      double l_front = 0, l_rear = 0;
      if (std::fabs(std::tan(steer_fl) - std::tan(steer_fr)) > 0.01) {
        l_front = std::tan(steer_fr) * std::tan(steer_fl) * st / (std::tan(steer_fl) - std::tan(steer_fr));
      }
      if (std::fabs(std::tan(steer_rl) - std::tan(steer_rr)) > 0.01) {
        l_rear = std::tan(steer_rr) * std::tan(steer_rl) * st / (std::tan(steer_rl) - std::tan(steer_rr));
      }
      const double w = v * (tan_front - tan_rear) / b;
      const double vel_steering_offset = (w * off) / r;
      const double sign = std::copysign(1.0, v);
      vel_fl = sign * std::hypot(v - w * st / 2, l_front * w) / r - vel_steering_offset;
      vel_fr = sign * std::hypot(v + w * st / 2, l_front * w) / r + vel_steering_offset;
      vel_rl = sign * std::hypot(v - w * st / 2, l_rear * w) / r - vel_steering_offset;
      vel_rr = sign * std::hypot(v + w * st / 2, l_rear * w) / r + vel_steering_offset;
    }
  }
  wheels_[0]->command = vel_fl;
  wheels_[1]->command = vel_fr;
  wheels_[2]->command = vel_rl;
  wheels_[3]->command = vel_rr;
  steering_[0]->command = steer_fl;
  steering_[1]->command = steer_fr;
  steering_[2]->command = steer_rl;
  steering_[3]->command = steer_rr;
}

std::vector<FourWheelSteeringController::OdomSample> FourWheelSteeringController::takeOdom() {
  return odom_out_.take();
}

}  // namespace tianracer_control
