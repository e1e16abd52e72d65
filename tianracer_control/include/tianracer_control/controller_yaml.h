// A ros_control controller YAML read without ROS (what `rosparam load` and the adapter in
// ros/controller_adapter.h do together), for hosts with no parameter server: the Python
// simulation and tools. ROS-free (yaml-cpp).
#ifndef TIANRACER_CONTROL_CONTROLLER_YAML_H
#define TIANRACER_CONTROL_CONTROLLER_YAML_H

#include <string>
#include <vector>

#include "tianracer_control/joint_controllers.h"

namespace tianracer_control {

/// The controllers under the namespace `ns` of a controller YAML, as the node reads them from
/// the parameter server once the file is loaded at the root (sim.launch does so): `ns` is a key
/// path such as "/tianracer" or "a/b" (leading and trailing '/' ignored; "" = the top level).
/// Every dictionary with a `type` key under it is a controller; `names` picks some (in that
/// order), empty = all (sorted by name, as the node lists them). Values are typed as rosparam
/// types them (YAML 1.1 plain scalars: ints, doubles, true/false/yes/no; quoted: strings).
/// Each spec holds the controller's whole dictionary as the parameter server would (its class
/// reads and checks its keys when created, naming this file and the controller's line).
/// Throws ControllerError naming the file and line: unreadable file or bad YAML, `ns` or a
/// named controller missing, parameters that are no dictionary or a type that is no string.
std::vector<ControllerSpec> loadControllerYamlFile(const std::string& path, const std::string& ns,
                                                   const std::vector<std::string>& names = {});
/// The same from YAML text; `source` names it in messages.
std::vector<ControllerSpec> loadControllerYaml(const std::string& yaml, const std::string& source,
                                               const std::string& ns,
                                               const std::vector<std::string>& names = {});

}  // namespace tianracer_control

#endif  // TIANRACER_CONTROL_CONTROLLER_YAML_H
