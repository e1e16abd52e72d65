// Ackermann steering kinematics: Twist (v, angular.z) -> hinge angles and rear wheel speeds.
// ROS-free. Frames follow REP-103: x forward, y left, z up; positive angles turn left.
#ifndef TIANRACER_CONTROL_ACKERMANN_H
#define TIANRACER_CONTROL_ACKERMANN_H

#include "tianracer_control/diagnostic.h"

namespace tianracer_control {

/// Steering geometry that cannot be used (a parameter, a URDF, a mesh); names the value.
using AckermannError = InputError;

/// The car's steering geometry. Defaults: the seed tianracer URDF.
struct AckermannGeometry {
  double wheelbase = 0.25;          // L: rear axle to the front hinge axis (m)
  double hinge_separation = 0.1366; // T: distance between the two steering hinges (m)
  double wheel_radius = 0.032;      // r: rear wheel radius (m)
  double rear_track = 0.168;        // Tr: distance between the rear wheel centres (m)
  double max_steering_angle = 0.6;  // m: joint limit of each hinge, |angle| <= m (rad)
  /// Rear axle midpoint P in the base frame (seed: about (-0.125, -0.0023)). The kinematics
  /// refer to P; odometry reports the base frame.
  double rear_axle_x = 0.0;
  double rear_axle_y = 0.0;
  /// Where the hinges really are. Textbook Ackermann assumes a symmetric car; CAD-exported URDFs
  /// are not (the seed's hinges are 2.6 mm apart in x and their midpoint is 4.7 mm left of P,
  /// which turns a left circle 1.4 % wide and a right one 1.3 % tight if ignored). In the rear
  /// axle frame (origin P, x forward, y left):
  ///   left hinge  (L - s, c + T/2),   right hinge (L + s, c - T/2)
  double hinge_skew_x = 0.0;    // s = (x_right_hinge - x_left_hinge) / 2 (m)
  double hinge_offset_y = 0.0;  // c = mean hinge y - y of P (m)

  /// Throws AckermannError naming the first bad value: L, r > 0; T, Tr >= 0; 0 < m < pi/2;
  /// |s| < L; |c| < L; all finite.
  void validate() const;
};

struct AckermannOptions {
  /// false (default, REP-103): angular.z is the yaw rate w, delta = atan(L w / v).
  /// true: angular.z is the bicycle steering angle delta itself (tianracer's TEB setup).
  bool angular_z_is_steering_angle = false;
  /// Rear wheels at v (1 -+ Tr tan(delta) / (2L)) / r instead of both at v / r.
  bool differential = false;
};

struct AckermannCommand {
  double left_steer = 0.0;         // left hinge angle (rad)
  double right_steer = 0.0;        // right hinge angle (rad)
  double left_wheel_omega = 0.0;   // left rear wheel (rad/s)
  double right_wheel_omega = 0.0;  // right rear wheel (rad/s)
  double delta = 0.0;              // bicycle steering angle after clamping (rad)
  double speed = 0.0;              // v (m/s), rear axle midpoint
  double yaw_rate = 0.0;           // achieved w = v tan(delta) / L (rad/s)
  bool clamped = false;            // the requested delta was beyond max_bicycle_angle
};

/// Bicycle model: delta = atan(L w / v); 0 when v == 0 (the car cannot turn in place).
/// Reversing (v < 0) keeps REP-103 semantics: positive w still turns the body left.
double steeringAngleFromYawRate(double wheelbase, double v, double yaw_rate);
/// Inverse: w = v tan(delta) / L.
double yawRateFromSteeringAngle(double wheelbase, double v, double delta);

/// Exact Ackermann (all wheel axes meet on the rear axle line), for any sign of delta. The
/// turning centre is (0, R), R = L / tan(delta), in the rear axle frame; a hinge at (dx, dy)
/// must point its wheel perpendicular to the ray from the centre:
///   tan(a) = dx / (R - dy) = dx tan(delta) / (L - dy tan(delta))
/// For a symmetric car (s = c = 0) that is the textbook
///   tan(delta_left)  = L tan(delta) / (L - T/2 tan(delta))
///   tan(delta_right) = L tan(delta) / (L + T/2 tan(delta))
/// i.e. cot(delta_left) = cot(delta) - T/(2L), cot(delta_right) = cot(delta) + T/(2L).
/// Turning left (delta > 0) the left wheel is the inner one (larger angle): delta_i = delta_left.
double leftWheelAngle(const AckermannGeometry& g, double delta);
double rightWheelAngle(const AckermannGeometry& g, double delta);
/// Inverses: the bicycle angle whose left (right) wheel angle is `angle`:
///   tan(delta) = L tan(a) / (dx + dy tan(a))
/// (symmetric: L tan(a) / (L + T/2 tan(a)) for the left, L tan(a) / (L - T/2 tan(a)) right).
double bicycleAngleFromLeft(const AckermannGeometry& g, double angle);
double bicycleAngleFromRight(const AckermannGeometry& g, double angle);

/// The largest delta turning left (inner left wheel at m) and the largest -delta turning right
/// (inner right wheel at -m):
///   left: bicycleAngleFromLeft(m),   right: -bicycleAngleFromRight(-m)
/// Equal for a symmetric car: atan(L tan(m) / (L + T/2 tan(m))).
double maxBicycleAngleLeft(const AckermannGeometry& g);
double maxBicycleAngleRight(const AckermannGeometry& g);
/// The smaller of the two: |delta| up to this turns either way. The tightest turn of the rear
/// axle midpoint both ways is then R_min = L / tan(delta_max).
double maxBicycleAngle(const AckermannGeometry& g);

/// Twist -> command. delta (from w, or angular_z itself in steering-angle mode) is clamped to
/// [-maxBicycleAngleRight, maxBicycleAngleLeft] (clamped = true), so that the inner wheel
/// reaches the joint limit either way; the wheel angles follow from the clamped delta. Rear
/// wheels: omega = v / r, or with `differential`
///   omega_left = v (1 - Tr tan(delta) / (2L)) / r,  omega_right = v (1 + Tr tan(delta) / (2L)) / r.
/// Non-finite inputs are treated as 0 (callers should reject them first).
AckermannCommand twistToAckermann(const AckermannGeometry& g, double v, double angular_z,
                                  const AckermannOptions& options = AckermannOptions());

/// The same from a bicycle angle: delta clamped as above, wheel angles and rear
/// wheel speeds for speed v. (The cmd_vel node ramps v while holding delta.)
AckermannCommand ackermannFromSteering(const AckermannGeometry& g, double v, double delta,
                                       bool differential = false);

}  // namespace tianracer_control

#endif  // TIANRACER_CONTROL_ACKERMANN_H
