#include "tianracer_control/controllers/speed_limiter.h"

#include <algorithm>

#include "tianracer_control/controller_params.h"

namespace tianracer_control {

namespace {
double ratio(double v, double before) { return before != 0.0 ? v / before : 1.0; }
// speed_limiter.cpp's clamp: min(max(lo, x), hi), defined (hi wins) when lo > hi.
double clamp(double x, double lo, double hi) { return std::min(std::max(lo, x), hi); }
}  // namespace

double SpeedLimiter::limit(double& v, double v0, double v1, double dt) const {
  const double before = v;
  limitJerk(v, v0, v1, dt);
  limitAcceleration(v, v0, dt);
  limitVelocity(v);
  return ratio(v, before);
}

double SpeedLimiter::limitVelocity(double& v) const {
  const double before = v;
  if (has_velocity_limits) v = clamp(v, min_velocity, max_velocity);
  return ratio(v, before);
}

double SpeedLimiter::limitAcceleration(double& v, double v0, double dt) const {
  const double before = v;
  if (has_acceleration_limits) {
    v = v0 + clamp(v - v0, min_acceleration * dt, max_acceleration * dt);
  }
  return ratio(v, before);
}

double SpeedLimiter::limitJerk(double& v, double v0, double v1, double dt) const {
  const double before = v;
  if (has_jerk_limits) {
    const double dv = v - v0;
    const double dv0 = v0 - v1;
    const double dt2 = 2.0 * dt * dt;
    v = v0 + dv0 + clamp(dv - dv0, min_jerk * dt2, max_jerk * dt2);
  }
  return ratio(v, before);
}

SpeedLimiter SpeedLimiter::read(ControllerParams& params, const std::string& ns) {
  SpeedLimiter l;
  const std::string p = ns + "/";
  l.has_velocity_limits = params.boolean(p + "has_velocity_limits").value_or(false);
  l.has_acceleration_limits = params.boolean(p + "has_acceleration_limits").value_or(false);
  l.has_jerk_limits = params.boolean(p + "has_jerk_limits").value_or(false);
  l.max_velocity = params.number(p + "max_velocity").value_or(0.0);
  l.min_velocity = params.number(p + "min_velocity").value_or(-l.max_velocity);
  l.max_acceleration = params.number(p + "max_acceleration").value_or(0.0);
  l.min_acceleration = params.number(p + "min_acceleration").value_or(-l.max_acceleration);
  l.max_jerk = params.number(p + "max_jerk").value_or(0.0);
  l.min_jerk = params.number(p + "min_jerk").value_or(-l.max_jerk);
  return l;
}

}  // namespace tianracer_control
