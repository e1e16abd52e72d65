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
  if (!std::isfinite(rear_axle_y)) fail("rear_axle_y", rear_axle_y, "must be finite");
  if (!std::isfinite(hinge_skew_x) || std::abs(hinge_skew_x) >= wheelbase) {
    fail("hinge_skew_x", hinge_skew_x, "must be smaller than the wheelbase in magnitude");
  }
  if (!std::isfinite(hinge_offset_y) || std::abs(hinge_offset_y) >= wheelbase) {
    fail("hinge_offset_y", hinge_offset_y, "must be smaller than the wheelbase in magnitude");
  }
}

double steeringAngleFromYawRate(double wheelbase, double v, double yaw_rate) {
  if (v == 0.0) return 0.0;
  return std::atan(wheelbase * yaw_rate / v);
}

double yawRateFromSteeringAngle(double wheelbase, double v, double delta) {
  return v * std::tan(delta) / wheelbase;
}

namespace {

// Hinge positions in the rear axle frame (see AckermannGeometry).
struct Hinge {
  double dx, dy;
};
Hinge leftHinge(const AckermannGeometry& g) {
  return {g.wheelbase - g.hinge_skew_x, g.hinge_offset_y + 0.5 * g.hinge_separation};
}
Hinge rightHinge(const AckermannGeometry& g) {
  return {g.wheelbase + g.hinge_skew_x, g.hinge_offset_y - 0.5 * g.hinge_separation};
}

// atan2 keeps the angle continuous should the denominator pass through 0 (inner wheel at 90 deg,
// unreachable within a valid limit); the sign of the numerator picks the side.
double wheelAngle(const AckermannGeometry& g, const Hinge& h, double delta) {
  const double t = std::tan(delta);
  return std::atan2(h.dx * t, g.wheelbase - h.dy * t);
}

double bicycleAngle(const AckermannGeometry& g, const Hinge& h, double angle) {
  const double t = std::tan(angle);
  return std::atan2(g.wheelbase * t, h.dx + h.dy * t);
}

}  // namespace

double leftWheelAngle(const AckermannGeometry& g, double delta) {
  return wheelAngle(g, leftHinge(g), delta);
}

double rightWheelAngle(const AckermannGeometry& g, double delta) {
  return wheelAngle(g, rightHinge(g), delta);
}

double bicycleAngleFromLeft(const AckermannGeometry& g, double angle) {
  return bicycleAngle(g, leftHinge(g), angle);
}

double bicycleAngleFromRight(const AckermannGeometry& g, double angle) {
  return bicycleAngle(g, rightHinge(g), angle);
}

double maxBicycleAngleLeft(const AckermannGeometry& g) {
  return bicycleAngleFromLeft(g, g.max_steering_angle);
}

double maxBicycleAngleRight(const AckermannGeometry& g) {
  return -bicycleAngleFromRight(g, -g.max_steering_angle);
}

double maxBicycleAngle(const AckermannGeometry& g) {
  return std::min(maxBicycleAngleLeft(g), maxBicycleAngleRight(g));
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
  const double left_limit = maxBicycleAngleLeft(g), right_limit = maxBicycleAngleRight(g);
  cmd.delta = std::clamp(delta, -right_limit, left_limit);
  cmd.clamped = delta > left_limit || delta < -right_limit;

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
