// PID controller with control_toolbox::Pid semantics. ROS-free.
#ifndef TIANRACER_CONTROL_PID_H
#define TIANRACER_CONTROL_PID_H

namespace tianracer_control {

/// Gains as ros_control YAML writes them (pid: {p, i, d, i_clamp, i_clamp_min, i_clamp_max,
/// antiwindup}). `i_clamp: c` means i_clamp_min = -|c|, i_clamp_max = |c| (see fromIClamp).
struct PidGains {
  double p = 0.0;
  double i = 0.0;
  double d = 0.0;
  double i_clamp_min = 0.0;  // bounds of the integral *term* i * I (units of the command)
  double i_clamp_max = 0.0;
  bool antiwindup = false;

  static PidGains fromIClamp(double p, double i, double d, double i_clamp, bool antiwindup = false);
};

/// control_toolbox::Pid, with the first-update derivative defined as zero.
///
/// Per update with error e_k and step dt > 0:
///   P = p * e_k
///   I_k = I_{k-1} + e_k * dt                         (integrator, rectangle rule)
///     antiwindup:  I_k = clamp(I_k, i_clamp_min/|i|, i_clamp_max/|i|)   (when i != 0)
///   i_term = i * I_k
///     no antiwindup: i_term = clamp(i_term, i_clamp_min, i_clamp_max)   (I_k itself may grow)
///   D = d * e_dot,  e_dot = (e_k - e_{k-1}) / dt,  e_dot = 0 on the first update after reset()
///   u = P + i_term + D
/// Without antiwindup the integrator keeps growing past the clamp (as in control_toolbox), so it
/// takes as long to unwind; with antiwindup it stops at the clamp.
///
/// computeCommand(e, e_dot, dt) takes the error derivative from the caller instead (as
/// control_toolbox's three-argument form; ros_controllers' position controller passes the
/// velocity error, which avoids the derivative kick of a setpoint step).
///
/// dt <= 0, a non-finite dt or a non-finite error: returns 0 and leaves the state unchanged.
class Pid {
 public:
  explicit Pid(const PidGains& gains = PidGains()) : gains_(gains) {}

  void setGains(const PidGains& gains) { gains_ = gains; }
  const PidGains& gains() const { return gains_; }

  double computeCommand(double error, double dt);
  double computeCommand(double error, double error_dot, double dt);

  /// Clears the integrator, the last error and the derivative history.
  void reset();

  double integrator() const { return i_error_; }
  double lastError() const { return p_error_; }
  double lastErrorDot() const { return d_error_; }
  double lastCommand() const { return command_; }

 private:
  double update(double error, double error_dot, double dt);

  PidGains gains_;
  double p_error_ = 0.0;  // last error
  double i_error_ = 0.0;  // integral of the error
  double d_error_ = 0.0;  // last error derivative
  double command_ = 0.0;
  bool has_last_error_ = false;
};

}  // namespace tianracer_control

#endif  // TIANRACER_CONTROL_PID_H
