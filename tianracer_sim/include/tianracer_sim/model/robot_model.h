// The robot as the simulator sees it: the URDF (parsed by urdfdom) plus the Gazebo extension
// tags and transmissions (parsed by tinyxml2) as plain structs. ROS-free.
#ifndef TIANRACER_SIM_MODEL_ROBOT_MODEL_H
#define TIANRACER_SIM_MODEL_ROBOT_MODEL_H

#include <functional>
#include <map>
#include <optional>
#include <stdexcept>
#include <string>
#include <vector>

#include <Eigen/Geometry>
// urdf::ModelInterfaceSharedPtr only: a source that reads the URDF's links and joints includes
// <urdf_model/model.h> itself (66k lines, 0.6 s in each of 68 sources that included it here).
#include <urdf_world/types.h>

#include <tianracer_assets/paths.h>

#include "tianracer_sim/common/element_lines.h"
#include "tianracer_sim/common/diagnostic.h"

namespace tinyxml2 {
class XMLElement;
}

namespace tianracer_sim {

/// Errors in a model file; the message names the file, element and value.
using ModelError = InputError;

/// A <plugin> element: filename, name and its child elements as text (whitespace trimmed).
struct PluginSpec {
  std::string name;
  std::string filename;
  std::map<std::string, std::string> params;
  std::string source;  // the model file (or parameter) it was read from
  int line = 0;
};

/// A <sensor> inside <gazebo reference="link">. Kept whole for the sensor code: its pose,
/// rate, the raw XML of the element (parsed by the lidar/camera loaders) and its plugins.
struct SensorSpec {
  std::string name;
  std::string type;  // ray, camera, depth, ...
  std::string link;
  Eigen::Isometry3d X_LS = Eigen::Isometry3d::Identity();  // sensor pose in its link frame
  double update_rate = 0.0;
  bool always_on = true;
  std::string xml;  // the <sensor> element, printed back
  /// The line in `source` of each element of `xml`, in document order (XmlReader::printCopy),
  /// so that a sensor's parser places an error at the bad element, not at the <sensor>.
  std::vector<int> xml_lines;
  std::vector<PluginSpec> plugins;
  std::string source;  // the model file (or parameter) it was read from; with `line`, the place
  int line = 0;        // of every message about the sensor
  /// Set when the sensor's own tags (<update_rate>, <pose>, <always_on>) are invalid: the
  /// message names the file, line, sensor and value. The robot loads; the sensor is left out.
  std::string error;
};

/// A sensor description that cannot be used; the message names the sensor, element and value.
using SensorError = InputError;

/// <gazebo reference="link"> surface, material and sensors. Unset optionals mean "Gazebo's default".
struct LinkExtension {
  std::optional<double> mu1, mu2, kp, kd, max_vel, min_depth;
  std::optional<Eigen::Vector3d> fdir1;
  std::optional<bool> self_collide;
  /// <gravity> (or the older <turnGravityOff>, inverted): false, the link feels no gravity
  /// (sdformat's parser_urdf.cc makes either the link's <gravity>).
  std::optional<bool> gravity;
  std::string material;  // e.g. "Gazebo/Red"
  std::vector<SensorSpec> sensors;
};

enum class JointInterface { kEffort, kVelocity, kPosition };

/// "EffortJointInterface" or "hardware_interface/EffortJointInterface" -> kEffort; nullopt if unknown.
std::optional<JointInterface> parseJointInterface(const std::string& text);
const char* toString(JointInterface iface);

/// transmission_interface/SimpleTransmission: joint = actuator / reduction.
struct TransmissionSpec {
  std::string name;
  std::string type;
  std::string joint;
  std::vector<JointInterface> joint_interfaces;
  std::string actuator;
  std::vector<JointInterface> actuator_interfaces;
  double mechanical_reduction = 1.0;
  int line = 0;
};

/// libgazebo_ros_control.so parameters.
struct RosControlSpec {
  std::string robot_namespace;                    // e.g. "/tianracer"
  std::string robot_param = "robot_description";
  double control_period = 0.0;                    // seconds; 0 = every physics step
  /// <eStopTopic>: a std_msgs/Bool topic under the namespace; "" = none.
  std::string e_stop_topic;
  /// <robotSimType> when the simulator runs it: gazebo_ros_control/DefaultRobotHWSim (also for
  /// any other, with a warning) or steer_bot_hardware_gazebo/SteerBotHardwareGazebo
  /// (sim/steer_bot_hw_sim.h).
  std::string robot_sim_type = "gazebo_ros_control/DefaultRobotHWSim";
};

/// libgazebo_ros_joint_state_publisher.so parameters (joint names with all whitespace removed).
struct JointStatePublisherSpec {
  std::vector<std::string> joint_names;
  double update_rate = 100.0;
  std::string robot_namespace;
};

struct RobotExtensions {
  std::map<std::string, LinkExtension> links;  // by link name
  std::vector<PluginSpec> model_plugins;       // every <gazebo><plugin> (also the known ones)
  std::optional<RosControlSpec> ros_control;
  std::optional<JointStatePublisherSpec> joint_state_publisher;
  std::vector<TransmissionSpec> transmissions;
};

/// Resolves mesh URIs: the one resolver (tianracer_assets/paths.h): package:// through
/// find_package, model:// in Gazebo's model path, file:// and absolute paths as given, relative
/// paths against base_dir (the model file's folder). Its errors are ModelErrors (InputError).
using MeshResolver = tianracer_assets::UriResolver;

struct RobotModel {
  urdf::ModelInterfaceSharedPtr urdf;
  RobotExtensions ext;
  std::string source;                              // file path, or the parameter name
  std::map<std::string, std::string> mesh_paths;   // URI as written -> resolved absolute path
  ElementLines lines;                              // where each <link> and <joint> stands
};

struct LoadOptions {
  MeshResolver resolver;
  WarningSink warn;                    // may be empty: warnings are then dropped
  bool require_meshes = true;          // a missing mesh file is an error (link and path named)
};

/// Parses a URDF string (already expanded) and its extensions; validates masses, inertias,
/// transmissions and mesh files. `source` names the input in error messages.
RobotModel loadRobotModel(const std::string& urdf_xml, const std::string& source,
                          const LoadOptions& options);

/// Loads a .urdf, or expands a .xacro by running the xacro tool first.
RobotModel loadRobotModelFile(const std::string& path, LoadOptions options);

/// Runs `xacro <path> [args...]` and returns the URDF; throws ModelError with xacro's stderr.
std::string expandXacro(const std::string& path, const std::vector<std::string>& args = {});
/// As above; what xacro prints on stderr while succeeding (deprecations...) goes to `warn`.
std::string expandXacro(const std::string& path, const std::vector<std::string>& args,
                        const WarningSink& warn);

/// Parses one SDF <sensor> element on `link` (a robot's <gazebo reference> or a world model's
/// <link>: SDF's <sensor> is the same in both) into the SensorSpec the sensor registry takes.
/// Throws ModelError "<source>:<line>: ..." for a sensor without name or type or a <plugin>
/// without filename; a bad <pose>, <update_rate> or <always_on> is kept in SensorSpec::error.
SensorSpec parseSensorElement(const tinyxml2::XMLElement* sensor, const std::string& link,
                              const std::string& source);

/// Parses one <plugin> element (filename, name, its children as text). Throws ModelError
/// "<source>:<line>: ..." for a plugin without filename.
PluginSpec parsePluginElement(const tinyxml2::XMLElement* plugin, const std::string& source);

/// The pose of link `to` in link `from` when only fixed joints lie between them (up and down
/// the tree); nullopt when a joint that moves lies between them or either is no link.
std::optional<Eigen::Isometry3d> fixedPose(const urdf::ModelInterface& model,
                                           const std::string& from, const std::string& to);

/// Parses only the extension tags (gazebo, transmission) of a URDF string; used by the fuzzer.
RobotExtensions parseExtensions(const std::string& urdf_xml, const std::string& source,
                                const WarningSink& warn);

}  // namespace tianracer_sim

#endif  // TIANRACER_SIM_MODEL_ROBOT_MODEL_H
