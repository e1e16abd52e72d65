// The pid/ keys of a ros_control YAML -> PidGains, with control_toolbox's rules. ROS-free.
#ifndef TIANRACER_CONTROL_PID_PARAMS_H
#define TIANRACER_CONTROL_PID_PARAMS_H

#include <optional>
#include <string>

#include "tianracer_control/controller_params.h"
#include "tianracer_control/pid.h"

namespace tianracer_control {

/// The pid/ keys as written in the YAML; unset = absent. Converted and checked by toPidGains().
struct PidParams {
  std::optional<double> p, i, d, i_clamp, i_clamp_min, i_clamp_max;
  std::optional<bool> antiwindup;
};

/// control_toolbox's Pid::init keys, each read as `reader.number(prefix + key)` (and
/// `boolean` for antiwindup): any reader of parameters with those two (a controller's YAML, the
/// hardware's pid_gains/<joint>).
template <class Reader>
PidParams readPidParams(Reader& reader, const std::string& prefix = "") {
  PidParams pid;
  pid.p = reader.number(prefix + "p");
  pid.i = reader.number(prefix + "i");
  pid.d = reader.number(prefix + "d");
  pid.i_clamp = reader.number(prefix + "i_clamp");
  pid.i_clamp_min = reader.number(prefix + "i_clamp_min");
  pid.i_clamp_max = reader.number(prefix + "i_clamp_max");
  pid.antiwindup = reader.boolean(prefix + "antiwindup");
  return pid;
}

/// pid/{p,i,d,i_clamp,i_clamp_min,i_clamp_max,antiwindup} -> gains, with control_toolbox's rules:
/// p is required; i, d default to 0; i_clamp_min/max override i_clamp (min = -|i_clamp|,
/// max = |i_clamp|); all clamps default to 0, which disables the integral term (warned when i != 0).
/// Throws ControllerError (naming `controller`) for a missing p, non-finite values or min > max.
PidGains toPidGains(const std::string& controller, const PidParams& params,
                    const WarningSink& warn = WarningSink());

/// The gains of a controller that needs them (control_toolbox::Pid::init(nh "pid")): reads
/// pid/..., throws ControllerError "pid/p is missing (<type> needs pid gains)" when p is absent,
/// then toPidGains().
/// `ns`: where the gains are (effort_controllers/JointGroupPositionController: <joint>/pid).
PidGains readPidGains(ControllerParams& params, const WarningSink& warn,
                      const std::string& ns = "pid");

}  // namespace tianracer_control

#endif  // TIANRACER_CONTROL_PID_PARAMS_H
