#include "tianracer_control/trajectory/spline_segment.h"

#include <stdexcept>

namespace tianracer_control {
namespace trajectory {
namespace {

using Coefficients = std::array<double, 6>;

Coefficients linear(double p0, double p1, double T) {
  return {p0, T == 0.0 ? 0.0 : (p1 - p0) / T, 0.0, 0.0, 0.0, 0.0};
}

Coefficients cubic(double p0, double v0, double p1, double v1, double T) {
  if (T == 0.0) return {p0, v0, 0.0, 0.0, 0.0, 0.0};
  const double T2 = T * T, T3 = T2 * T;
  return {p0, v0, (-3.0 * p0 + 3.0 * p1 - 2.0 * v0 * T - v1 * T) / T2,
          (2.0 * p0 - 2.0 * p1 + v0 * T + v1 * T) / T3, 0.0, 0.0};
}

Coefficients quintic(double p0, double v0, double a0, double p1, double v1, double a1,
                     double T) {
  if (T == 0.0) return {p0, v0, 0.5 * a0, 0.0, 0.0, 0.0};
  const double T2 = T * T, T3 = T2 * T, T4 = T3 * T, T5 = T4 * T;
  return {p0,
          v0,
          0.5 * a0,
          (-20.0 * p0 + 20.0 * p1 - 3.0 * a0 * T2 + a1 * T2 - 12.0 * v0 * T - 8.0 * v1 * T) /
              (2.0 * T3),
          (30.0 * p0 - 30.0 * p1 + 3.0 * a0 * T2 - 2.0 * a1 * T2 + 16.0 * v0 * T + 14.0 * v1 * T) /
              (2.0 * T4),
          (-12.0 * p0 + 12.0 * p1 - a0 * T2 + a1 * T2 - 6.0 * v0 * T - 6.0 * v1 * T) /
              (2.0 * T5)};
}

// The polynomial at s, with its first two derivatives (plain powers, as upstream evaluates it,
// so that the numbers match to the last bit).
void evaluate(const Coefficients& c, double s, double& p, double& v, double& a) {
  const double s2 = s * s, s3 = s2 * s, s4 = s3 * s, s5 = s4 * s;
  p = c[0] + s * c[1] + s2 * c[2] + s3 * c[3] + s4 * c[4] + s5 * c[5];
  v = c[1] + 2.0 * s * c[2] + 3.0 * s2 * c[3] + 4.0 * s3 * c[4] + 5.0 * s4 * c[5];
  a = 2.0 * c[2] + 6.0 * s * c[3] + 12.0 * s2 * c[4] + 20.0 * s3 * c[5];
}

}  // namespace

SplineSegment::SplineSegment(double start_time, const State& start_state, double end_time,
                             const State& end_state) {
  init(start_time, start_state, end_time, end_state);
}

void SplineSegment::init(double start_time, const State& start_state, double end_time,
                         const State& end_state) {
  const char* what = "Quintic spline segment can't be constructed: ";
  if (end_time < start_time) {
    throw std::invalid_argument(std::string(what) + "end_time < start_time.");
  }
  if (start_state.position.empty() || end_state.position.empty()) {
    throw std::invalid_argument(std::string(what) + "Endpoint positions can't be empty.");
  }
  if (start_state.position.size() != end_state.position.size()) {
    throw std::invalid_argument(std::string(what) + "Endpoint positions size mismatch.");
  }
  const std::size_t n = start_state.position.size();
  const bool has_vel = !start_state.velocity.empty() && !end_state.velocity.empty();
  const bool has_acc = !start_state.acceleration.empty() && !end_state.acceleration.empty();
  if (has_vel && start_state.velocity.size() != n) {
    throw std::invalid_argument(std::string(what) + "Start state velocity size mismatch.");
  }
  if (has_vel && end_state.velocity.size() != n) {
    throw std::invalid_argument(std::string(what) + "End state velocity size mismatch.");
  }
  if (has_acc && start_state.acceleration.size() != n) {
    throw std::invalid_argument(std::string(what) + "Start state acceleration size mismatch.");
  }
  if (has_acc && end_state.acceleration.size() != n) {
    throw std::invalid_argument(std::string(what) + "End state acceleration size mismatch.");
  }

  start_time_ = start_time;
  duration_ = end_time - start_time;
  time_from_start_ = start_state.time_from_start;
  coefs_.resize(n);
  for (std::size_t i = 0; i < n; ++i) {
    const double p0 = start_state.position[i], p1 = end_state.position[i];
    if (!has_vel) {
      coefs_[i] = linear(p0, p1, duration_);
    } else if (!has_acc) {
      coefs_[i] = cubic(p0, start_state.velocity[i], p1, end_state.velocity[i], duration_);
    } else {
      coefs_[i] = quintic(p0, start_state.velocity[i], start_state.acceleration[i], p1,
                          end_state.velocity[i], end_state.acceleration[i], duration_);
    }
  }
}

void SplineSegment::sample(double time, State& state) const {
  const std::size_t n = coefs_.size();
  state.position.resize(n);
  state.velocity.resize(n);
  state.acceleration.resize(n);
  const double s = time - start_time_;
  for (std::size_t i = 0; i < n; ++i) {
    double unused = 0.0;
    if (s < 0.0) {
      evaluate(coefs_[i], 0.0, state.position[i], unused, unused);
      state.velocity[i] = 0.0;
      state.acceleration[i] = 0.0;
    } else if (s > duration_) {
      evaluate(coefs_[i], duration_, state.position[i], unused, unused);
      state.velocity[i] = 0.0;
      state.acceleration[i] = 0.0;
    } else {
      evaluate(coefs_[i], s, state.position[i], state.velocity[i], state.acceleration[i]);
    }
  }
}

}  // namespace trajectory
}  // namespace tianracer_control
