// The parameter server as the source of a robot's controllers (simulator/robot_setup.h decides
// which controllers a robot gets, by the same rules as the Python environment's YAML); the
// specs themselves are read by tianracer_control's ROS adapter.
#ifndef TIANRACER_SIM_ROS_CONTROLLER_PARAMS_H
#define TIANRACER_SIM_ROS_CONTROLLER_PARAMS_H

#include <string>
#include <vector>

#include <ros/node_handle.h>

#include "tianracer_sim/simulator/robot_setup.h"

namespace tianracer_sim {

/// Names of the controllers defined under `ns` (every struct member with a `type` key), sorted.
std::vector<std::string> listControllers(const ros::NodeHandle& ns);

/// ControlParams on the parameter server; relative namespaces resolve against the node's.
class RosControlParams : public ControlParams {
 public:
  std::vector<std::string> list(const std::string& ns) const override;
  std::vector<tianracer_control::ControllerSpec> load(
      const std::string& ns, const std::vector<std::string>& names) const override;
  std::string resolve(const std::string& ns) const override;
};

}  // namespace tianracer_sim

#endif  // TIANRACER_SIM_ROS_CONTROLLER_PARAMS_H
