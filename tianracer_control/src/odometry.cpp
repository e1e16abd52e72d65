#include "tianracer_control/odometry.h"

#include <cmath>

#include "tianracer_control/joint_controllers.h"  // shortestAngularDistance

namespace tianracer_control {

namespace {
double sinc(double x) {
  // Taylor series below 1e-4: the error term x^4/120 is far below double precision there.
  return std::abs(x) < 1e-4 ? 1.0 - x * x / 6.0 : std::sin(x) / x;
}
}  // namespace

BicycleOdometry::BicycleOdometry(const AckermannGeometry& geometry) : geometry_(geometry) {}

void BicycleOdometry::reset(double x, double y, double yaw) {
  // P = base - Rot(yaw) b, b = -(rear_axle_x, rear_axle_y).
  const double c = std::cos(yaw), s = std::sin(yaw);
  px_ = x + c * geometry_.rear_axle_x - s * geometry_.rear_axle_y;
  py_ = y + s * geometry_.rear_axle_x + c * geometry_.rear_axle_y;
  yaw_ = yaw;
  v_ = 0.0;
  w_ = 0.0;
  distance_ = 0.0;
  has_positions_ = false;
}

bool BicycleOdometry::update(double left_rear_omega, double right_rear_omega, double left_hinge,
                             double right_hinge, double dt) {
  if (!std::isfinite(left_rear_omega) || !std::isfinite(right_rear_omega) ||
      !std::isfinite(left_hinge) || !std::isfinite(right_hinge)) {
    return false;
  }
  const double v = geometry_.wheel_radius * 0.5 * (left_rear_omega + right_rear_omega);
  const double delta = 0.5 * (bicycleAngleFromLeft(geometry_, left_hinge) +
                              bicycleAngleFromRight(geometry_, right_hinge));
  return integrate(v, yawRateFromSteeringAngle(geometry_.wheelbase, v, delta), dt);
}

bool BicycleOdometry::updateFromPositions(double left_rear_position, double right_rear_position,
                                          double left_hinge, double right_hinge, double dt) {
  if (!std::isfinite(left_rear_position) || !std::isfinite(right_rear_position)) return false;
  if (!has_positions_) {
    last_left_ = left_rear_position;
    last_right_ = right_rear_position;
    has_positions_ = true;
    return false;
  }
  if (!(dt > 0.0) || !std::isfinite(dt)) return false;
  auto step = [](double from, double to) {
    const double d = to - from;
    return std::abs(d) > M_PI ? shortestAngularDistance(from, to) : d;
  };
  const double left_omega = step(last_left_, left_rear_position) / dt;
  const double right_omega = step(last_right_, right_rear_position) / dt;
  last_left_ = left_rear_position;
  last_right_ = right_rear_position;
  return update(left_omega, right_omega, left_hinge, right_hinge, dt);
}

bool BicycleOdometry::integrate(double v, double w, double dt) {
  if (!(dt > 0.0) || !std::isfinite(dt) || !std::isfinite(v) || !std::isfinite(w)) return false;
  const double half = 0.5 * w * dt;
  const double chord = v * dt * sinc(half);
  px_ += chord * std::cos(yaw_ + half);
  py_ += chord * std::sin(yaw_ + half);
  yaw_ += w * dt;
  v_ = v;
  w_ = w;
  distance_ += std::abs(v) * dt;
  return true;
}

double BicycleOdometry::x() const {
  return px_ - std::cos(yaw_) * geometry_.rear_axle_x + std::sin(yaw_) * geometry_.rear_axle_y;
}
double BicycleOdometry::y() const {
  return py_ - std::sin(yaw_) * geometry_.rear_axle_x - std::cos(yaw_) * geometry_.rear_axle_y;
}
double BicycleOdometry::heading() const { return shortestAngularDistance(0.0, yaw_); }
double BicycleOdometry::linearVelocity() const { return v_ + w_ * geometry_.rear_axle_y; }
double BicycleOdometry::lateralVelocity() const { return -geometry_.rear_axle_x * w_; }

}  // namespace tianracer_control
