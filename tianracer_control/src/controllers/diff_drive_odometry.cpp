#include "tianracer_control/controllers/diff_drive_odometry.h"

#include <cmath>

namespace tianracer_control {

void RollingMean::add(double x) {
  samples_.push_back(x);
  sum_ += x;
  if (samples_.size() > size_) {
    sum_ -= samples_.front();
    samples_.pop_front();
  }
}

DiffDriveOdometry::DiffDriveOdometry(std::size_t size)
    : window_(size), linear_acc_(size), angular_acc_(size) {}

void DiffDriveOdometry::init(double t) {
  linear_acc_ = RollingMean(window_);
  angular_acc_ = RollingMean(window_);
  timestamp_ = t;
}

void DiffDriveOdometry::resetPose(double left_pos, double right_pos) {
  x_ = y_ = heading_ = linear_ = angular_ = 0.0;
  left_wheel_old_pos_ = left_pos * left_wheel_radius_;
  right_wheel_old_pos_ = right_pos * right_wheel_radius_;
}

bool DiffDriveOdometry::update(double left_pos, double right_pos, double t) {
  const double left_cur = left_pos * left_wheel_radius_;
  const double right_cur = right_pos * right_wheel_radius_;
  const double left_travel = left_cur - left_wheel_old_pos_;
  const double right_travel = right_cur - right_wheel_old_pos_;
  left_wheel_old_pos_ = left_cur;
  right_wheel_old_pos_ = right_cur;
  return integrate((right_travel + left_travel) * 0.5, (right_travel - left_travel) / wheel_separation_,
                   t);
}

bool DiffDriveOdometry::integrate(double linear, double angular, double t) {
  integrateExact(linear, angular);
  const double dt = t - timestamp_;
  if (dt < 0.0001) return false;  // interval too small to integrate with
  timestamp_ = t;
  linear_acc_.add(linear / dt);
  angular_acc_.add(angular / dt);
  linear_ = linear_acc_.mean();
  angular_ = angular_acc_.mean();
  return true;
}

void DiffDriveOdometry::updateOpenLoop(double linear, double angular, double t) {
  linear_ = linear;
  angular_ = angular;
  const double dt = t - timestamp_;
  timestamp_ = t;
  integrateExact(linear * dt, angular * dt);
}

void DiffDriveOdometry::setWheelParams(double wheel_separation, double left_wheel_radius,
                                       double right_wheel_radius) {
  wheel_separation_ = wheel_separation;
  left_wheel_radius_ = left_wheel_radius;
  right_wheel_radius_ = right_wheel_radius;
}

void DiffDriveOdometry::setVelocityRollingWindowSize(std::size_t size) {
  window_ = size;
  linear_acc_ = RollingMean(window_);
  angular_acc_ = RollingMean(window_);
}

void DiffDriveOdometry::integrateRungeKutta2(double linear, double angular) {
  const double direction = heading_ + angular * 0.5;
  x_ += linear * std::cos(direction);
  y_ += linear * std::sin(direction);
  heading_ += angular;
}

void DiffDriveOdometry::integrateExact(double linear, double angular) {
  if (std::fabs(angular) < 1e-6) {
    integrateRungeKutta2(linear, angular);
    return;
  }
  const double heading_old = heading_;
  const double r = linear / angular;
  heading_ += angular;
  x_ += r * (std::sin(heading_) - std::sin(heading_old));
  y_ += -r * (std::cos(heading_) - std::cos(heading_old));
}

}  // namespace tianracer_control
