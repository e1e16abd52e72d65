// diff_drive_controller's Odometry (ros_controllers noetic-devel,
// diff_drive_controller/src/odometry.cpp). ROS-free.
//   update(left_pos, right_pos, t): wheel travel since the last call (position * radius),
//     linear = (dr + dl) / 2, angular = (dr - dl) / separation, integrated exactly (an arc;
//     second-order Runge-Kutta when |angular| < 1e-6); then, unless t - last t < 0.0001 s, the
//     velocities are the rolling means (velocity_rolling_window_size samples) of linear/dt and
//     angular/dt.
//   updateOpenLoop(linear, angular, t): the commanded velocities integrated over t - last t.
#ifndef TIANRACER_CONTROL_CONTROLLERS_DIFF_DRIVE_ODOMETRY_H
#define TIANRACER_CONTROL_CONTROLLERS_DIFF_DRIVE_ODOMETRY_H

#include <cstddef>
#include <deque>

namespace tianracer_control {

/// boost::accumulators' rolling_mean over the last `size` samples.
class RollingMean {
 public:
  explicit RollingMean(std::size_t size = 10) : size_(size < 1 ? 1 : size) {}
  void add(double x);
  double mean() const { return samples_.empty() ? 0.0 : sum_ / samples_.size(); }

 private:
  std::size_t size_;
  std::deque<double> samples_;
  double sum_ = 0.0;
};

class DiffDriveOdometry {
 public:
  explicit DiffDriveOdometry(std::size_t velocity_rolling_window_size = 10);

  /// Clears the velocity averages and takes t as the last time (the pose stays: upstream's init).
  void init(double t);
  /// Pose to 0 and the wheels' last positions to (left_pos, right_pos) (a sim reset).
  void resetPose(double left_pos, double right_pos);
  bool update(double left_pos, double right_pos, double t);
  /// The tail of update() for a travel already computed (ackermann_steering_controller's
  /// odometry: linear = rear wheel travel, angular = tan(steer) linear / wheel_separation_h):
  /// integrates, then averages linear/dt and angular/dt unless dt < 0.0001 s.
  bool integrate(double linear, double angular, double t);
  void updateOpenLoop(double linear, double angular, double t);
  void setWheelParams(double wheel_separation, double left_wheel_radius, double right_wheel_radius);
  void setVelocityRollingWindowSize(std::size_t size);

  double x() const { return x_; }
  double y() const { return y_; }
  double heading() const { return heading_; }
  double linear() const { return linear_; }
  double angular() const { return angular_; }

 private:
  void integrateExact(double linear, double angular);
  void integrateRungeKutta2(double linear, double angular);

  double timestamp_ = 0.0;
  double x_ = 0.0, y_ = 0.0, heading_ = 0.0;
  double linear_ = 0.0, angular_ = 0.0;
  double wheel_separation_ = 0.0, left_wheel_radius_ = 0.0, right_wheel_radius_ = 0.0;
  double left_wheel_old_pos_ = 0.0, right_wheel_old_pos_ = 0.0;
  std::size_t window_;
  RollingMean linear_acc_, angular_acc_;
};

}  // namespace tianracer_control

#endif  // TIANRACER_CONTROL_CONTROLLERS_DIFF_DRIVE_ODOMETRY_H
