// diff_drive_controller's SpeedLimiter (ros_controllers noetic-devel,
// diff_drive_controller/src/speed_limiter.cpp), also ackermann_steering_controller's: limits a
// velocity command v given the last two commands v0, v1 and the period dt, jerk first, then
// acceleration, then velocity:
//   jerk:  dv = v - v0, dv0 = v0 - v1, da = clamp(dv - dv0, min_jerk 2dt^2, max_jerk 2dt^2),
//          v = v0 + dv0 + da
//   acceleration: v = v0 + clamp(v - v0, min_acceleration dt, max_acceleration dt)
//   velocity: v = clamp(v, min_velocity, max_velocity)
// Each only when its has_*_limits is set. ROS-free.
#ifndef TIANRACER_CONTROL_CONTROLLERS_SPEED_LIMITER_H
#define TIANRACER_CONTROL_CONTROLLERS_SPEED_LIMITER_H

#include <string>

namespace tianracer_control {

class ControllerParams;

struct SpeedLimiter {
  bool has_velocity_limits = false;
  bool has_acceleration_limits = false;
  bool has_jerk_limits = false;
  double min_velocity = 0.0, max_velocity = 0.0;
  double min_acceleration = 0.0, max_acceleration = 0.0;
  double min_jerk = 0.0, max_jerk = 0.0;

  /// Limits v in place; returns the factor applied (v / v_in, 1 when v_in is 0).
  double limit(double& v, double v0, double v1, double dt) const;
  double limitVelocity(double& v) const;
  double limitAcceleration(double& v, double v0, double dt) const;
  double limitJerk(double& v, double v0, double v1, double dt) const;

  /// Reads <ns>/has_velocity_limits, ..., <ns>/max_jerk, <ns>/min_jerk as the controllers do:
  /// each min_* defaults to -max_* (the max as read). e.g. ns = "linear/x".
  static SpeedLimiter read(ControllerParams& params, const std::string& ns);
};

}  // namespace tianracer_control

#endif  // TIANRACER_CONTROL_CONTROLLERS_SPEED_LIMITER_H
