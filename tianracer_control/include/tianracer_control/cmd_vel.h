// What the cmd_vel node does with each Twist or Ackermann drive command and each tick, without
// ROS: validation, limits, command timeout, acceleration and steering-rate ramps. Times are
// seconds of sim time.
#ifndef TIANRACER_CONTROL_CMD_VEL_H
#define TIANRACER_CONTROL_CMD_VEL_H

#include "tianracer_control/ackermann.h"

namespace tianracer_control {

struct CmdVelLimits {
  double max_speed = 3.0;    // |v| limit (m/s); larger commands are clamped
  double max_accel = 0.0;    // |dv/dt| limit (m/s^2); 0 = none
  double cmd_timeout = 0.5;  // s without a Twist -> speed target 0, steering held; 0 = never
};

/// An ackermann_msgs/AckermannDrive's fields as the processor takes them.
struct AckermannDriveInput {
  double speed = 0.0;                    // m/s at the rear axle's centre
  double steering_angle = 0.0;           // bicycle angle (rad, + left)
  double steering_angle_velocity = 0.0;  // |d delta/dt| limit (rad/s); 0 = as fast as possible
  double acceleration = 0.0;             // |dv/dt| limit (m/s^2); 0 = as fast as possible
};

/// What became of an Ackermann drive command. rejected: some value (or t) was NaN/inf; the
/// command is dropped and nothing changes. Otherwise the clamps that applied.
struct AckermannDriveResult {
  bool rejected = false;
  bool speed_clamped = false;     // |speed| > max_speed
  bool steering_clamped = false;  // beyond the inner wheel's joint limit
};

/// Twist (or Ackermann drive command) in, Ackermann command out.
///  - setTwist(): non-finite components reject the whole message (returns kRejected, nothing
///    changes); |v| is clamped to max_speed. The steering angle is fixed here: in yaw-rate mode
///    delta = atan(L w / v) with the clamped v, so the commanded yaw rate holds at the speed
///    actually driven; ramping the speed later keeps the path's curvature.
///  - update(t): after cmd_timeout without a Twist the speed target becomes 0 and the steering
///    is held; the speed moves toward its target at most max_accel * dt. Time going backwards
///    (sim reset) resets everything.
///  - setAckermann(): the same clamps, timeout and reset for an AckermannDrive. The steering
///    angle is clamped to the joint limits on arrival; a non-zero steering_angle_velocity
///    moves the steering toward it at that rate, and a non-zero acceleration limits the speed
///    ramp (together with max_accel, the smaller wins). A Twist afterwards steers at once.
///  - Both inputs drive the same car: the latest message wins. twoSourcesActive(t) is true
///    while both have sent within the last cmd_timeout (1 s when the timeout is off).
class CmdVelProcessor {
 public:
  enum class Input { kAccepted, kSpeedClamped, kRejected };

  CmdVelProcessor(const AckermannGeometry& geometry, const AckermannOptions& options,
                  const CmdVelLimits& limits);

  Input setTwist(double linear_x, double angular_z, double t);
  AckermannDriveResult setAckermann(const AckermannDriveInput& drive, double t);
  bool twoSourcesActive(double t) const;
  AckermannCommand update(double t);
  void reset();

  bool timedOut() const { return timed_out_; }
  double speed() const { return v_out_; }

 private:
  AckermannGeometry geometry_;
  AckermannOptions options_;
  CmdVelLimits limits_;
  double v_target_ = 0.0;
  double delta_ = 0.0;  // requested bicycle angle (clamped by ackermannFromSteering)
  double delta_out_ = 0.0;  // steering after the rate limit
  double steering_rate_ = 0.0;  // rad/s; 0 = steer at once
  double accel_ = 0.0;          // the command's own speed ramp (m/s^2); 0 = none
  double v_out_ = 0.0;
  double last_twist_source_t_ = -1e300, last_ackermann_t_ = -1e300;
  double last_twist_t_ = 0.0;
  double last_update_t_ = 0.0;
  bool has_twist_ = false;
  bool has_update_ = false;
  bool timed_out_ = false;
  /// Common part of both inputs once validated and clamped.
  void command(double v, double delta, double t);
};

}  // namespace tianracer_control

#endif  // TIANRACER_CONTROL_CMD_VEL_H
