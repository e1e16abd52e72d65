// A ros_control controller YAML read without ROS (what `rosparam load` and the adapter in
// ros/controller_adapter.h do together), for hosts with no parameter server: the Python
// simulation and tools. ROS-free (yaml-cpp).
#ifndef TIANRACER_CONTROL_CONTROLLER_YAML_H
#define TIANRACER_CONTROL_CONTROLLER_YAML_H

#include <optional>
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

/// The names of the controllers under `ns` (sorted, as loadControllerYaml takes them when given
/// none); nullopt when the YAML has no key path `ns`. Throws ControllerError for YAML that does
/// not parse.
std::optional<std::vector<std::string>> listControllerYaml(const std::string& yaml,
                                                           const std::string& source,
                                                           const std::string& ns);

/// The text of a file; throws ControllerError "<what> <path>: cannot be read".
std::string readTextFile(const std::string& path, const std::string& what);

/// The top-level keys of a ros_control YAML file (~control_config: what `rosparam load` put at
/// the launch file's namespace), and those that define controllers (a dictionary with at least
/// one member that has a `type`).
struct ControlConfigKeys {
  std::string file;
  std::vector<std::string> keys;
  std::vector<std::string> with_controllers;
  std::string error;  // the file could not be read or is no YAML dictionary ("" = fine)
};
ControlConfigKeys readControlConfigKeys(const std::string& file);

}  // namespace tianracer_control

#endif  // TIANRACER_CONTROL_CONTROLLER_YAML_H
