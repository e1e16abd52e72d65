#include "tianracer_control/trajectory/controller_options.h"

#include <cmath>
#include <sstream>

namespace tianracer_control {
namespace trajectory {
namespace {

double readChecked(ControllerParams& params, const std::string& key, double fallback,
                   bool zero_allowed, const char* what) {
  const std::optional<double> value = params.number(key);
  if (!value) return fallback;
  if (!std::isfinite(*value) || *value < 0.0 || (!zero_allowed && *value == 0.0)) {
    std::ostringstream msg;
    msg << params.prefix() << key << " must be " << what << ", got " << *value;
    throw ControllerError(msg.str());
  }
  return *value;
}

}  // namespace

TrajectoryControllerOptions readTrajectoryControllerOptions(
    ControllerParams& params, const std::vector<std::string>& joint_names) {
  TrajectoryControllerOptions options;
  options.state_publish_rate =
      readChecked(params, "state_publish_rate", 50.0, false, "a finite rate > 0 [Hz]");
  options.action_monitor_rate =
      readChecked(params, "action_monitor_rate", 20.0, false, "a finite rate > 0 [Hz]");
  options.stop_trajectory_duration =
      readChecked(params, "stop_trajectory_duration", 0.0, true, "a finite duration >= 0 [s]");
  options.allow_partial_joints_goal = params.boolean("allow_partial_joints_goal").value_or(false);
  options.default_tolerances = readSegmentTolerances(params, joint_names);
  return options;
}

}  // namespace trajectory
}  // namespace tianracer_control
