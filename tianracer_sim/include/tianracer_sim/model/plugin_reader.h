// The one reader of a <plugin>'s parameters (PluginSpec::params), as gazebo_plugins read their
// SDF elements (sdf::Element::Get; gazebo_plugins' getParameter in gazebo_ros_utils.h): each
// read marks the name, a value that cannot be used raises InputError placed at the <plugin>
// ("<file>:<line>: <context>: <name> ..."), and finish() warns once about each parameter that
// nothing read. Every sensor and drive plugin reads its parameters through it.
#ifndef TIANRACER_SIM_MODEL_PLUGIN_READER_H
#define TIANRACER_SIM_MODEL_PLUGIN_READER_H

#include <initializer_list>
#include <optional>
#include <set>
#include <string>

#include <Eigen/Core>

#include "tianracer_sim/common/diagnostic.h"
#include "tianracer_sim/model/robot_model.h"

namespace tianracer_sim {

/// What a gazebo_ros plugin's Load makes of a <robotNamespace> given but empty.
enum class NamespaceRule {
  kAsGiven,       // the value as given: an empty one is the root (GazeboRosP3D, the IMU
                  // sensor, bumper, range, block_laser, velodyne, skid steer, planar move,
                  // hector's, gazebo_ros_control, joint_state_publisher)
  kEmptyIsModel,  // the model's name: GetRobotNamespace (gazebo_ros_utils.h: gazebo_ros_laser,
                  // gpu_laser, the cameras) and GazeboRos (the diff drive)
};

/// Where PluginReader::robotNamespace() took the namespace from.
enum class NamespaceFrom { kMissing, kGiven, kModel };

class PluginReader {
 public:
  /// `context` starts every message after the place, e.g. "contact sensor 'b' of model 'm'".
  PluginReader(const PluginSpec& plugin, std::string context, WarningSink warn);

  const PluginSpec& plugin() const { return plugin_; }
  /// The plugin's file name without its folder, e.g. "libgazebo_ros_bumper.so".
  std::string fileName() const;

  /// Whether the parameter is given (and marks it read).
  bool has(const std::string& key);
  /// The value, trimmed; nullopt when not given.
  std::optional<std::string> text(const std::string& key);
  /// Sets *out to the value when given; returns whether it was.
  bool text(const std::string& key, std::string* out);
  /// A frame name without leading '/' (as gazebo_ros plugins strip tf_prefix slashes);
  /// `fallback` when not given or empty.
  std::string frame(const std::string& key, const std::string& fallback);
  /// A finite number; fails on text that is not one ("'x' is not a number") or inf/nan
  /// ("x is not finite"), and with `non_negative` on a value below 0 ("x must be >= 0").
  bool number(const std::string& key, double* out, bool non_negative = false);
  /// Three finite numbers.
  bool vector3(const std::string& key, Eigen::Vector3d* out);
  /// <robotNamespace>, the one reading of it for every plugin, by the plugin's `rule`: given,
  /// *ns is its trimmed value (kGiven); given but empty under kEmptyIsModel, *ns is left and
  /// the namespace is the model's name (kModel: the caller, who knows the name, applies it);
  /// missing, *ns keeps the plugin's default (kMissing).
  NamespaceFrom robotNamespace(NamespaceRule rule, std::string* ns);
  /// true/1 or false/0, any case.
  bool boolean(const std::string& key, bool* out);
  /// Names that are read elsewhere or mean nothing here (not reported by finish()).
  void ignore(std::initializer_list<const char*> keys);

  /// Throws InputError at the <plugin>: "<file>:<line>: <context>: <message>".
  [[noreturn]] void fail(const std::string& message) const;
  /// Warns once: "<file>:<line>: <context>: <message>".
  void warn(const std::string& message);
  /// Warns about each parameter not read: "<name> is not a parameter of <file name>, ignored".
  void finish();

 private:
  std::string place() const;

  const PluginSpec& plugin_;
  std::string context_;
  WarnOnce warn_;
  std::set<std::string> read_;
};

}  // namespace tianracer_sim

#endif  // TIANRACER_SIM_MODEL_PLUGIN_READER_H
