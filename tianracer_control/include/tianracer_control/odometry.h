// Wheel odometry of an Ackermann car through the bicycle model. ROS-free, deterministic.
#ifndef TIANRACER_CONTROL_ODOMETRY_H
#define TIANRACER_CONTROL_ODOMETRY_H

#include "tianracer_control/ackermann.h"

namespace tianracer_control {

/// Integrates the planar pose of the base frame from rear wheel speeds and hinge angles.
///
/// Per update:
///   v     = r (omega_left + omega_right) / 2                     (rear axle midpoint speed)
///   delta = (bicycleAngleFromLeft(a_left) + bicycleAngleFromRight(a_right)) / 2
///   w     = v tan(delta) / L
/// The rear axle midpoint P moves on an exact arc over dt (constant v and w):
///   chord = v dt sinc(w dt / 2),  sinc(x) = sin(x) / x  (-> 1 - x^2/6 for small x)
///   P += chord (cos(yaw + w dt / 2), sin(yaw + w dt / 2)),   yaw += w dt
/// which is x += v/w (sin(yaw') - sin(yaw)), y -= v/w (cos(yaw') - cos(yaw)) without the
/// cancellation of that form as w -> 0. The base frame origin is at b = -(rear_axle_x,
/// rear_axle_y) from P in the body frame:
///   base = P + Rot(yaw) b; its velocity in the base frame is (v - w b_y, w b_x, w).
class BicycleOdometry {
 public:
  explicit BicycleOdometry(const AckermannGeometry& geometry = AckermannGeometry());

  void setGeometry(const AckermannGeometry& geometry) { geometry_ = geometry; }
  const AckermannGeometry& geometry() const { return geometry_; }

  /// Pose of the base frame; velocities and the travelled distance back to 0.
  void reset(double x = 0.0, double y = 0.0, double yaw = 0.0);

  /// Rear wheel angular speeds (rad/s), hinge angles (rad), interval dt (s). dt <= 0 or a
  /// non-finite input: ignored, returns false.
  bool update(double left_rear_omega, double right_rear_omega, double left_hinge,
              double right_hinge, double dt);

  /// Same, from rear wheel joint positions (rad, unwrapped as joint_states carries them): the
  /// speeds are the position differences over dt, so the distance is exact whatever the sample
  /// rate. The first call (and the first after reset()) only stores the positions. A step larger
  /// than pi is taken as a wrap (for publishers that wrap continuous joints into [-pi, pi)); at
  /// 50 Hz that only misreads wheels turning faster than 157 rad/s.
  bool updateFromPositions(double left_rear_position, double right_rear_position,
                           double left_hinge, double right_hinge, double dt);

  /// Rear axle midpoint speed v (m/s) and yaw rate w (rad/s) over dt.
  bool integrate(double v, double w, double dt);

  double x() const;  // base frame in the odometry frame (m)
  double y() const;
  double yaw() const { return yaw_; }  // rad, not wrapped (heading() wraps)
  double heading() const;               // yaw wrapped into [-pi, pi)
  double linearVelocity() const;                  // v - w b_y, base frame (m/s)
  double lateralVelocity() const;                 // w b_x, base frame (m/s)
  double angularVelocity() const { return w_; }   // rad/s
  double distance() const { return distance_; }   // |path length| of P so far (m)

 private:
  AckermannGeometry geometry_;
  double px_ = 0.0, py_ = 0.0, yaw_ = 0.0;  // rear axle midpoint pose
  double v_ = 0.0, w_ = 0.0;
  double distance_ = 0.0;
  bool has_positions_ = false;
  double last_left_ = 0.0, last_right_ = 0.0;
};

}  // namespace tianracer_control

#endif  // TIANRACER_CONTROL_ODOMETRY_H
