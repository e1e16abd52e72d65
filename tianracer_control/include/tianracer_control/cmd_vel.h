// What the cmd_vel node does with each Twist and each tick, without ROS: validation, limits,
// command timeout, acceleration ramp. Times are seconds of sim time.
#ifndef TIANRACER_CONTROL_CMD_VEL_H
#define TIANRACER_CONTROL_CMD_VEL_H

#include "tianracer_control/ackermann.h"

namespace tianracer_control {

struct CmdVelLimits {
  double max_speed = 3.0;    // |v| limit (m/s); larger commands are clamped
  double max_accel = 0.0;    // |dv/dt| limit (m/s^2); 0 = none
  double cmd_timeout = 0.5;  // s without a Twist -> speed target 0, steering held; 0 = never
};

/// Twist in, Ackermann command out.
///  - setTwist(): non-finite components reject the whole message (returns kRejected, nothing
///    changes); |v| is clamped to max_speed. The steering angle is fixed here: in yaw-rate mode
///    delta = atan(L w / v) with the clamped v, so the commanded yaw rate holds at the speed
///    actually driven; ramping the speed later keeps the path's curvature.
///  - update(t): after cmd_timeout without a Twist the speed target becomes 0 and the steering
///    is held; the speed moves toward its target at most max_accel * dt. Time going backwards
///    (sim reset) resets everything.
class CmdVelProcessor {
 public:
  enum class Input { kAccepted, kSpeedClamped, kRejected };

  CmdVelProcessor(const AckermannGeometry& geometry, const AckermannOptions& options,
                  const CmdVelLimits& limits);

  Input setTwist(double linear_x, double angular_z, double t);
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
  double v_out_ = 0.0;
  double last_twist_t_ = 0.0;
  double last_update_t_ = 0.0;
  bool has_twist_ = false;
  bool has_update_ = false;
  bool timed_out_ = false;
};

}  // namespace tianracer_control

#endif  // TIANRACER_CONTROL_CMD_VEL_H
