#include "tianracer_control/cmd_vel.h"

#include <algorithm>
#include <cmath>

namespace tianracer_control {

CmdVelProcessor::CmdVelProcessor(const AckermannGeometry& geometry,
                                 const AckermannOptions& options, const CmdVelLimits& limits)
    : geometry_(geometry), options_(options), limits_(limits) {}

void CmdVelProcessor::reset() {
  v_target_ = 0.0;
  delta_ = 0.0;
  delta_out_ = 0.0;
  steering_rate_ = 0.0;
  accel_ = 0.0;
  v_out_ = 0.0;
  last_twist_source_t_ = last_ackermann_t_ = -1e300;
  has_twist_ = false;
  has_update_ = false;
  timed_out_ = false;
}

CmdVelProcessor::Input CmdVelProcessor::setTwist(double linear_x, double angular_z, double t) {
  if (!std::isfinite(linear_x) || !std::isfinite(angular_z) || !std::isfinite(t)) {
    return Input::kRejected;
  }
  if (has_update_ && t < last_update_t_) reset();  // sim reset
  Input result = Input::kAccepted;
  double v = linear_x;
  if (limits_.max_speed > 0.0 && std::abs(v) > limits_.max_speed) {
    v = std::copysign(limits_.max_speed, v);
    result = Input::kSpeedClamped;
  }
  steering_rate_ = 0.0;
  accel_ = 0.0;
  command(v,
          options_.angular_z_is_steering_angle
              ? angular_z
              : steeringAngleFromYawRate(geometry_.wheelbase, v, angular_z),
          t);
  last_twist_source_t_ = t;
  return result;
}

AckermannDriveResult CmdVelProcessor::setAckermann(const AckermannDriveInput& d, double t) {
  AckermannDriveResult result;
  if (!std::isfinite(d.speed) || !std::isfinite(d.steering_angle) ||
      !std::isfinite(d.steering_angle_velocity) || !std::isfinite(d.acceleration) ||
      !std::isfinite(t)) {
    result.rejected = true;
    return result;
  }
  if (has_update_ && t < last_update_t_) reset();  // sim reset
  double v = d.speed;
  if (limits_.max_speed > 0.0 && std::abs(v) > limits_.max_speed) {
    v = std::copysign(limits_.max_speed, v);
    result.speed_clamped = true;
  }
  // Clamped on arrival, so that a rate-limited steering never chases an angle it cannot reach.
  const double delta = std::clamp(d.steering_angle, -maxBicycleAngleRight(geometry_),
                                  maxBicycleAngleLeft(geometry_));
  result.steering_clamped = delta != d.steering_angle;
  // The message's rates are magnitudes ("positive ... in either direction").
  steering_rate_ = std::abs(d.steering_angle_velocity);
  accel_ = std::abs(d.acceleration);
  command(v, delta, t);
  last_ackermann_t_ = t;
  return result;
}

void CmdVelProcessor::command(double v, double delta, double t) {
  v_target_ = v;
  delta_ = delta;
  last_twist_t_ = t;
  has_twist_ = true;
  timed_out_ = false;
}

bool CmdVelProcessor::twoSourcesActive(double t) const {
  const double window = limits_.cmd_timeout > 0.0 ? limits_.cmd_timeout : 1.0;
  return t - last_twist_source_t_ <= window && t - last_ackermann_t_ <= window;
}

AckermannCommand CmdVelProcessor::update(double t) {
  if (has_update_ && t < last_update_t_) reset();
  const double dt = has_update_ ? t - last_update_t_ : 0.0;
  last_update_t_ = t;
  has_update_ = true;

  if (has_twist_ && limits_.cmd_timeout > 0.0 && t - last_twist_t_ > limits_.cmd_timeout) {
    timed_out_ = true;
    v_target_ = 0.0;  // the steering (delta_) is held
  }
  double accel = limits_.max_accel;
  if (accel_ > 0.0) accel = accel > 0.0 ? std::min(accel, accel_) : accel_;
  if (accel > 0.0) {
    const double step = accel * dt;
    v_out_ += std::clamp(v_target_ - v_out_, -step, step);
  } else {
    v_out_ = v_target_;
  }
  if (steering_rate_ > 0.0) {
    const double step = steering_rate_ * dt;
    delta_out_ += std::clamp(delta_ - delta_out_, -step, step);
  } else {
    delta_out_ = delta_;
  }
  return ackermannFromSteering(geometry_, v_out_, delta_out_, options_.differential);
}

}  // namespace tianracer_control
