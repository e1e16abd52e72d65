// Controllers by type name (pluginlib's role in ros_control): a type string maps to the class's
// create(). A new controller type is one file under controllers/ plus one line in
// controller_registry.cpp's builtinControllers(). ROS-free.
#ifndef TIANRACER_CONTROL_CONTROLLER_REGISTRY_H
#define TIANRACER_CONTROL_CONTROLLER_REGISTRY_H

#include <map>
#include <memory>
#include <string>
#include <utility>
#include <vector>

#include "tianracer_control/controller.h"

namespace tianracer_control {

/// Builds a controller from its context; throws ControllerError naming the controller.
using ControllerFactory = std::unique_ptr<Controller> (*)(ControllerContext& context);

class ControllerRegistry {
 public:
  /// Registers `type` (e.g. "effort_controllers/JointPositionController").
  void add(const std::string& type, ControllerFactory factory);

  /// The registered types, in registration order.
  std::vector<std::string> types() const;
  bool has(const std::string& type) const;

  /// Builds a controller from its spec. `joints` holds the joints that have a transmission, by
  /// name. Throws ControllerError, naming the controller, for an empty name or type, an unknown
  /// type (listing the known ones), and whatever the class refuses (a missing joint, a joint not
  /// in `joints`, an interface mismatch, bad parameters). Keys the class did not read go to
  /// `warn` ("controller 'c': key 'k' is not used by <type>, ignored").
  std::unique_ptr<Controller> create(const ControllerSpec& spec,
                                     std::map<std::string, JointHandle*>& joints,
                                     const WarningSink& warn = WarningSink(),
                                     const urdf::ModelInterface* robot_description = nullptr) const;

 private:
  std::vector<std::pair<std::string, ControllerFactory>> factories_;
};

/// The controller types the simulator runs (ros_controllers' names).
const ControllerRegistry& builtinControllers();

}  // namespace tianracer_control

#endif  // TIANRACER_CONTROL_CONTROLLER_REGISTRY_H
