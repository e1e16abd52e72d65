#include "tianracer_control/ackermann.h"

#include <algorithm>
#include <cmath>
#include <sstream>

namespace tianracer_control {

void AckermannGeometry::validate() const {
  auto fail = [](const char* what, double value, const char* rule) {
    std::ostringstream os;
    os << "Ackermann geometry: " << what << " = " << value << " " << rule;
    throw AckermannError(os.str());
  };
  if (!std::isfinite(wheelbase) || wheelbase <= 0.0) fail("wheelbase", wheelbase, "must be > 0");
  if (!std::isfinite(hinge_separation) || hinge_separation < 0.0) {
    fail("hinge_separation", hinge_separation, "must be >= 0");
  }
  if (!std::isfinite(wheel_radius) || wheel_radius <= 0.0) {
    fail("wheel_radius", wheel_radius, "must be > 0");
  }
  if (!std::isfinite(rear_track) || rear_track < 0.0) fail("rear_track", rear_track, "must be >= 0");
  if (!std::isfinite(max_steering_angle) || max_steering_angle <= 0.0 ||
      max_steering_angle >= M_PI / 2) {
    fail("max_steering_angle", max_steering_angle, "must be in (0, pi/2)");
  }
  if (!std::isfinite(rear_axle_x)) fail("rear_axle_x", rear_axle_x, "must be finite");
}

double steeringAngleFromYawRate(double wheelbase, double v, double yaw_rate) {
  if (v == 0.0) return 0.0;
  return std::atan(wheelbase * yaw_rate / v);
}

double yawRateFromSteeringAngle(double wheelbase, double v, double delta) {
  return v * std::tan(delta) / wheelbase;
}

// atan2 keeps the angle continuous should the denominator pass through 0 (inner wheel at 90 deg,
// unreachable within a valid limit); the sign of the numerator picks the side.
double leftWheelAngle(const AckermannGeometry& g, double delta) {
  const double t = std::tan(delta);
  const double L = g.wheelbase;
  return std::atan2(L * t, L - 0.5 * g.hinge_separation * t);
}

double rightWheelAngle(const AckermannGeometry& g, double delta) {
  const double t = std::tan(delta);
  const double L = g.wheelbase;
  return std::atan2(L * t, L + 0.5 * g.hinge_separation * t);
}

double bicycleAngleFromLeft(const AckermannGeometry& g, double angle) {
  const double t = std::tan(angle);
  const double L = g.wheelbase;
  return std::atan2(L * t, L + 0.5 * g.hinge_separation * t);
}

double bicycleAngleFromRight(const AckermannGeometry& g, double angle) {
  const double t = std::tan(angle);
  const double L = g.wheelbase;
  return std::atan2(L * t, L - 0.5 * g.hinge_separation * t);
}

double maxBicycleAngle(const AckermannGeometry& g) {
  // The inner wheel of a left turn is the left one: solve leftWheelAngle(delta) = m.
  return bicycleAngleFromLeft(g, g.max_steering_angle);
}

AckermannCommand twistToAckermann(const AckermannGeometry& g, double v, double angular_z,
                                  const AckermannOptions& options) {
  if (!std::isfinite(v)) v = 0.0;
  if (!std::isfinite(angular_z)) angular_z = 0.0;
  const double requested = options.angular_z_is_steering_angle
                               ? angular_z
                               : steeringAngleFromYawRate(g.wheelbase, v, angular_z);
  return ackermannFromSteering(g, v, requested, options.differential);
}

AckermannCommand ackermannFromSteering(const AckermannGeometry& g, double v, double delta,
                                       bool differential) {
  if (!std::isfinite(v)) v = 0.0;
  if (!std::isfinite(delta)) delta = 0.0;

  AckermannCommand cmd;
  const double limit = maxBicycleAngle(g);
  cmd.delta = std::clamp(delta, -limit, limit);
  cmd.clamped = std::abs(delta) > limit;

  const double m = g.max_steering_angle;
  // At |delta| = limit the inner wheel is at m up to rounding; keep it inside the joint limit.
  cmd.left_steer = std::clamp(leftWheelAngle(g, cmd.delta), -m, m);
  cmd.right_steer = std::clamp(rightWheelAngle(g, cmd.delta), -m, m);

  cmd.speed = v;
  cmd.yaw_rate = yawRateFromSteeringAngle(g.wheelbase, v, cmd.delta);
  const double omega = v / g.wheel_radius;
  if (differential) {
    const double k = g.rear_track * std::tan(cmd.delta) / (2.0 * g.wheelbase);
    cmd.left_wheel_omega = omega * (1.0 - k);
    cmd.right_wheel_omega = omega * (1.0 + k);
  } else {
    cmd.left_wheel_omega = omega;
    cmd.right_wheel_omega = omega;
  }
  return cmd;
}

}  // namespace tianracer_control
