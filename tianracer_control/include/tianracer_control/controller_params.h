// A controller's parameters without ROS: the tree the parameter server holds under
// /<ns>/<controller> (XmlRpcValue's kinds), and the reader each controller class uses to take its
// own keys from it, as ros_controllers' init() reads controller_nh.
#ifndef TIANRACER_CONTROL_CONTROLLER_PARAMS_H
#define TIANRACER_CONTROL_CONTROLLER_PARAMS_H

#include <functional>
#include <map>
#include <optional>
#include <set>
#include <stdexcept>
#include <string>
#include <vector>

#include "tianracer_control/diagnostic.h"  // InputError, WarningSink

namespace tianracer_control {

/// A configuration error; the message starts with "line <n>: controller '<name>': " (the line
/// when known, diagnostic.h's one format).
using ControllerError = InputError;

/// One value of a parameter tree: absent, bool, int, double, string, list or dictionary (the
/// kinds of XmlRpcValue; kOther stands for the ones no controller reads, e.g. a date).
class ParamValue {
 public:
  enum class Kind { kNone, kBool, kInt, kDouble, kString, kList, kDict, kOther };
  using Dict = std::map<std::string, ParamValue>;
  using List = std::vector<ParamValue>;

  ParamValue() = default;
  ParamValue(bool v) : kind_(Kind::kBool), bool_(v) {}           // NOLINT: a value is a tree
  ParamValue(int v) : kind_(Kind::kInt), int_(v) {}              // NOLINT
  ParamValue(double v) : kind_(Kind::kDouble), double_(v) {}     // NOLINT
  ParamValue(const char* v) : kind_(Kind::kString), string_(v) {}  // NOLINT
  ParamValue(std::string v) : kind_(Kind::kString), string_(std::move(v)) {}  // NOLINT
  static ParamValue list(List items = List());
  static ParamValue dict();
  static ParamValue other();

  Kind kind() const { return kind_; }
  bool isNone() const { return kind_ == Kind::kNone; }
  bool asBool() const { return bool_; }
  int asInt() const { return int_; }
  double asDouble() const { return double_; }
  const std::string& asString() const { return string_; }
  /// The value as ros::NodeHandle::getParam reads a double: an int or a double; nullopt for
  /// another kind.
  std::optional<double> asNumber() const;
  const List& items() const { return list_; }
  const Dict& members() const { return dict_; }

  /// The member `key`, created (absent) when missing; an absent value becomes a dictionary.
  ParamValue& operator[](const std::string& key);
  /// The member `key` of a dictionary, nullptr when there is none (or this is no dictionary).
  const ParamValue* find(const std::string& key) const;
  /// Takes the member out (e.g. the "type" key before the controller reads the rest).
  void erase(const std::string& key) { dict_.erase(key); }

  /// "a bool", "an int", "a double", "a string", "a list", "a dictionary", "an unsupported value".
  const char* typeName() const;

 private:
  Kind kind_ = Kind::kNone;
  bool bool_ = false;
  int int_ = 0;
  double double_ = 0.0;
  std::string string_;
  List list_;
  Dict dict_;
};

/// One entry of a ros_control YAML, e.g.
///   left_steering_hinge_position_controller:
///     type: effort_controllers/JointPositionController
///     joint: left_steering_hinge_joint
///     pid: {p: 1.0, i: 0.0, d: 0.05}
/// `params` is the whole entry (type included, if it was there); each controller class reads
/// the keys it knows from it.
struct ControllerSpec {
  std::string name;
  std::string type;
  ParamValue params = ParamValue::dict();
  std::string source;  // the file it was read from, where known ("" = the parameter server)
  int line = 0;        // source line where known (0 = unknown)
};

/// What keeps `v` from being read as a finite number, as a phrase that follows the key ("is a
/// string, not a number", "is nan, not a finite number"); "" when it is one. The readers of
/// the simulated hardware's parameters (DefaultRobotHWSim, SteerBotHardwareGazebo) share it
/// and keep their own policy (warn and skip, or refuse).
std::string finiteNumberProblem(const ParamValue& v);

/// A number as parameter errors quote it (operator<<'s default: 6 significant digits).
std::string numberText(double x);

/// What a controller class reads its parameters through (controller_nh.getParam without ROS).
/// Keys are paths, "pid/p". A key of the wrong kind throws ControllerError naming the
/// controller and the key ("controller 'c': pid/p must be a number, got a string"); every key
/// read is recorded, so that the keys no reader asked for can be reported.
class ControllerParams {
 public:
  explicit ControllerParams(const ControllerSpec& spec) : spec_(spec) {}

  const std::string& name() const { return spec_.name; }
  const std::string& type() const { return spec_.type; }
  /// "<source>:<line>: controller '<name>': " (diagnostic.h's formatLocation: the parts known)
  std::string prefix() const;

  /// An int or a double; nullopt when absent.
  std::optional<double> number(const std::string& key);
  /// A number > 0 (`fallback` when absent); throws ControllerError "... <key> must be a
  /// positive number, got <x>" for zero, a negative or a non-finite value.
  double positiveNumber(const std::string& key, double fallback);
  std::optional<std::string> text(const std::string& key);
  std::optional<bool> boolean(const std::string& key);
  /// A list of strings (upstream's getParam(key, std::vector<std::string>)); nullopt when
  /// absent. Throws for another kind or an item that is not a string.
  std::optional<std::vector<std::string>> textList(const std::string& key);
  /// The value itself, for the readers of compound keys; null when absent.
  const ParamValue* value(const std::string& key) { return lookup(key); }

  /// Keys present that no read asked for, depth first in key order ("type" is the registry's).
  /// The members of a dictionary nobody read are not listed again.
  std::vector<std::string> unread() const;

 private:
  const ParamValue* lookup(const std::string& key);

  const ControllerSpec& spec_;
  std::set<std::string> read_;
};

/// "controller '<name>': "
std::string controllerPrefix(const std::string& name);

}  // namespace tianracer_control

#endif  // TIANRACER_CONTROL_CONTROLLER_PARAMS_H
