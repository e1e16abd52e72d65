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
  v_out_ = 0.0;
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
  v_target_ = v;
  delta_ = options_.angular_z_is_steering_angle
               ? angular_z
               : steeringAngleFromYawRate(geometry_.wheelbase, v, angular_z);
  last_twist_t_ = t;
  has_twist_ = true;
  timed_out_ = false;
  return result;
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
  if (limits_.max_accel > 0.0) {
    const double step = limits_.max_accel * dt;
    v_out_ += std::clamp(v_target_ - v_out_, -step, step);
  } else {
    v_out_ = v_target_;
  }
  return ackermannFromSteering(geometry_, v_out_, delta_, options_.differential);
}

}  // namespace tianracer_control
