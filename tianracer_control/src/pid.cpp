#include "tianracer_control/pid.h"

#include <algorithm>
#include <cmath>

namespace tianracer_control {
namespace {
// std::clamp is undefined for lo > hi; bad gains are rejected on load, this keeps update() total.
double clampTo(double x, double lo, double hi) { return std::min(std::max(x, lo), hi); }
}  // namespace

PidGains PidGains::fromIClamp(double p, double i, double d, double i_clamp, bool antiwindup) {
  PidGains g;
  g.p = p;
  g.i = i;
  g.d = d;
  g.i_clamp_min = -std::abs(i_clamp);
  g.i_clamp_max = std::abs(i_clamp);
  g.antiwindup = antiwindup;
  return g;
}

double Pid::computeCommand(double error, double dt) {
  if (!(dt > 0.0) || !std::isfinite(dt) || !std::isfinite(error)) return 0.0;
  const double error_dot = has_last_error_ ? (error - p_error_) / dt : 0.0;
  return update(error, error_dot, dt);
}

double Pid::computeCommand(double error, double error_dot, double dt) {
  if (!(dt > 0.0) || !std::isfinite(dt) || !std::isfinite(error) || !std::isfinite(error_dot)) {
    return 0.0;
  }
  return update(error, error_dot, dt);
}

double Pid::update(double error, double error_dot, double dt) {
  p_error_ = error;
  d_error_ = error_dot;
  has_last_error_ = true;

  i_error_ += dt * error;
  if (gains_.antiwindup && gains_.i != 0.0) {
    const double a = std::abs(gains_.i);
    i_error_ = clampTo(i_error_, gains_.i_clamp_min / a, gains_.i_clamp_max / a);
  }
  double i_term = gains_.i * i_error_;
  if (!gains_.antiwindup) i_term = clampTo(i_term, gains_.i_clamp_min, gains_.i_clamp_max);

  command_ = gains_.p * error + i_term + gains_.d * error_dot;
  return command_;
}

void Pid::reset() {
  p_error_ = 0.0;
  i_error_ = 0.0;
  d_error_ = 0.0;
  command_ = 0.0;
  has_last_error_ = false;
}

}  // namespace tianracer_control
