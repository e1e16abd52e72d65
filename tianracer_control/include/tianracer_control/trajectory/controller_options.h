// joint_trajectory_controller's parameters (JointTrajectoryController::init), read without ROS
// from the controller's parameter tree. ROS-free.
#ifndef TIANRACER_CONTROL_TRAJECTORY_CONTROLLER_OPTIONS_H
#define TIANRACER_CONTROL_TRAJECTORY_CONTROLLER_OPTIONS_H

#include <string>
#include <vector>

#include "tianracer_control/controller_params.h"
#include "tianracer_control/trajectory/tolerances.h"

namespace tianracer_control {
namespace trajectory {

struct TrajectoryControllerOptions {
  double state_publish_rate = 50.0;       // [Hz] ~state
  double action_monitor_rate = 20.0;      // [Hz] goal status
  double stop_trajectory_duration = 0.0;  // [s] 0: hold where the joints are; > 0: ramp to rest
  bool allow_partial_joints_goal = false;
  SegmentTolerances default_tolerances;   // constraints/...
};

/// state_publish_rate, action_monitor_rate, stop_trajectory_duration, allow_partial_joints_goal
/// and constraints/ (readSegmentTolerances), with upstream's defaults. Upstream divides by the
/// rates unchecked; here a rate <= 0 or non-finite, or a negative or non-finite
/// stop_trajectory_duration, throws ControllerError naming the key and value.
TrajectoryControllerOptions readTrajectoryControllerOptions(
    ControllerParams& params, const std::vector<std::string>& joint_names);

}  // namespace trajectory
}  // namespace tianracer_control

#endif  // TIANRACER_CONTROL_TRAJECTORY_CONTROLLER_OPTIONS_H
