// One robot set-up for every host: the ROS node (start-up and spawn_urdf_model) and the Python
// environment decide a robot's name, its ros_control namespace, where its controllers'
// parameters are read and which controllers it gets by the same rules, from the same kind of
// source: the parameter server's tree (the node) or the controller YAML read as `rosparam
// load` puts it on the server (Python, tools). ROS-free.
#ifndef TIANRACER_SIM_SIMULATOR_ROBOT_SETUP_H
#define TIANRACER_SIM_SIMULATOR_ROBOT_SETUP_H

#include <optional>
#include <string>
#include <vector>

#include <tianracer_control/controller_yaml.h>
#include <tianracer_control/joint_controllers.h>

#include "tianracer_sim/model/robot_model.h"

namespace tianracer_sim {

using tianracer_control::ControlConfigKeys;
using tianracer_control::readControlConfigKeys;

/// Where the controllers' parameters are read: namespaces are ROS names ("/tianracer", or
/// "tianracer" relative to the host's namespace).
class ControlParams {
 public:
  virtual ~ControlParams() = default;
  /// The names of the controllers defined under `ns` (every dictionary with a `type` key),
  /// sorted; none when nothing is there.
  virtual std::vector<std::string> list(const std::string& ns) const = 0;
  /// The specs of `names` under `ns`. Throws ControllerError naming a controller that has no
  /// parameters there.
  virtual std::vector<tianracer_control::ControllerSpec> load(
      const std::string& ns, const std::vector<std::string>& names) const = 0;
  /// `ns` as a full name, for messages and the controller_manager's namespace ("/tianracer").
  virtual std::string resolve(const std::string& ns) const = 0;
};

/// A controller YAML file read as `rosparam load` puts it at the root of the parameter server
/// (tianracer_control/controller_yaml.h, the one YAML reader); no file: no controllers.
class YamlControlParams : public ControlParams {
 public:
  /// Reads `file` ("" = none). Throws ControllerError naming the file when it cannot be read or
  /// does not parse.
  explicit YamlControlParams(std::string file);
  std::vector<std::string> list(const std::string& ns) const override;
  std::vector<tianracer_control::ControllerSpec> load(
      const std::string& ns, const std::vector<std::string>& names) const override;
  std::string resolve(const std::string& ns) const override;

 private:
  std::string file_, text_;
};

/// What the host was asked for (the node's ~ parameters, spawn_urdf_model's name, EnvConfig).
struct RobotSetupRequest {
  /// spawn_urdf_model's model name: the robot's name, whatever the model says.
  std::string spawn_name;
  /// ~robot_name / EnvConfig::robot_name: "" = the gazebo_ros_control namespace, else the URDF's
  /// name. A name other than the robotNamespace is warned (the controllers stay under the
  /// namespace).
  std::string robot_name;
  /// ~control_namespace / EnvConfig::control_namespace: where the controllers are read; unset =
  /// the robot's namespace, or the one key of control_config that defines controllers.
  std::optional<std::string> control_namespace;
  /// ~controllers / EnvConfig::controllers: which ones; unset = every controller defined there.
  std::optional<std::vector<std::string>> controllers;
  /// The controller YAML that was loaded (~control_config), for the namespace rule and messages.
  std::string control_config;
  /// A robot spawned through spawn_urdf_model with neither controllers nor a namespace given
  /// runs none until a spawner starts them through <ns>/controller_manager/, as in Gazebo.
  bool waits_for_spawner = false;
};

/// What a robot gets.
struct RobotSetup {
  std::string name;        // unique among the models
  std::string ns;          // its ros_control namespace, "/tianracer"
  std::string control_ns;  // where its controllers' parameters are, "/tianracer"
  std::vector<tianracer_control::ControllerSpec> controllers;
  std::vector<std::string> notes;     // choices worth a line at start-up
  std::vector<std::string> warnings;  // what the user likely did not mean
};

/// The rules, in order:
///  - name: spawn_name, else robot_name, else the gazebo_ros_control robotNamespace, else the
///    URDF's name;
///  - ns: the robotNamespace, else "/<name>" (gazebo_ros_control's default is the model's name);
///  - control_ns: control_namespace, else ns when controllers are defined there, else the one
///    top-level key of control_config that defines controllers (the shipped YAML is keyed
///    `tianracer` whatever the car is called), else ns;
///  - controllers: those asked for, else every one under control_ns (none when waits_for_spawner);
///    none found for a model with gazebo_ros_control is a warning naming what was searched.
/// Throws ControllerError as ControlParams::load does.
RobotSetup setUpRobot(const RobotModel& model, const RobotSetupRequest& request,
                      const ControlParams& params);

/// Where a robot's controllers are read when no control namespace is given (the rule above).
std::string chooseControlNamespace(const std::string& robot_ns, bool robot_ns_has_controllers,
                                   const ControlConfigKeys& config);

/// The start-up warning for a robot with gazebo_ros_control that gets no controller: names the
/// namespace searched and the YAML's top-level keys, and what to pass.
std::string noControllersWarning(const std::string& robot, const std::string& searched,
                                 const ControlConfigKeys& config);

}  // namespace tianracer_sim

#endif  // TIANRACER_SIM_SIMULATOR_ROBOT_SETUP_H
