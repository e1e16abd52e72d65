// What ros_controllers' PID joint controllers (effort_controllers' JointPositionController and
// JointVelocityController, velocity_controllers/JointPositionController) publish on `state`
// (control_msgs/JointControllerState): at the end of every update whose count since the
// controller was made is a multiple of 10 (upstream's `loop_count_ % 10 == 0`, never reset on
// restart), the set point, the process value and its derivative, the error, the period, the PID's
// output before any limit, and the gains (getGains: i_clamp is i_clamp_max). ROS-free: the ROS
// side (joint_command_ros.cpp) publishes each new sample once.
#ifndef TIANRACER_CONTROL_CONTROLLERS_PID_STATE_H
#define TIANRACER_CONTROL_CONTROLLERS_PID_STATE_H

#include <cstdint>

#include "tianracer_control/pid.h"

namespace tianracer_control {

struct PidStateSample {
  std::uint64_t seq = 0;  // samples taken so far; 0: none yet
  double set_point = 0.0, process_value = 0.0, process_value_dot = 0.0, error = 0.0;
  double time_step = 0.0, command = 0.0;
  PidGains gains;
};

class PidStateSource {
 public:
  virtual ~PidStateSource() = default;
  /// The last sample (PidStateSample::seq tells a new one).
  const PidStateSample& pidState() const { return state_; }

 protected:
  /// Called once per update, after the PID: keeps this update's values when the update count
  /// is a multiple of 10.
  void recordPidState(double set_point, double process_value, double process_value_dot,
                      double error, double time_step, double command, const PidGains& gains) {
    if (loop_count_++ % 10 != 0) return;
    state_.seq += 1;
    state_.set_point = set_point;
    state_.process_value = process_value;
    state_.process_value_dot = process_value_dot;
    state_.error = error;
    state_.time_step = time_step;
    state_.command = command;
    state_.gains = gains;
  }

 private:
  std::uint64_t loop_count_ = 0;
  PidStateSample state_;
};

}  // namespace tianracer_control

#endif  // TIANRACER_CONTROL_CONTROLLERS_PID_STATE_H
