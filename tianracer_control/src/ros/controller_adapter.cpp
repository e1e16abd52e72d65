#include "tianracer_control/ros/controller_adapter.h"

#include <cmath>
#include <sstream>

#include <ros/console.h>

namespace tianracer_control {

namespace {

using XmlRpc::XmlRpcValue;

// XmlRpcValue's conversions are non-const: read from a copy.
ParamValue toParamValue(XmlRpcValue v) {
  switch (v.getType()) {
    case XmlRpcValue::TypeBoolean:
      return ParamValue(static_cast<bool>(v));
    case XmlRpcValue::TypeInt:
      return ParamValue(static_cast<int>(v));
    case XmlRpcValue::TypeDouble:
      return ParamValue(static_cast<double>(v));
    case XmlRpcValue::TypeString:
      return ParamValue(static_cast<std::string>(v));
    case XmlRpcValue::TypeArray: {
      ParamValue::List items;
      for (int i = 0; i < v.size(); ++i) items.push_back(toParamValue(v[i]));
      return ParamValue::list(std::move(items));
    }
    case XmlRpcValue::TypeStruct: {
      ParamValue tree = ParamValue::dict();
      for (auto it = v.begin(); it != v.end(); ++it) tree[it->first] = toParamValue(it->second);
      return tree;
    }
    default:
      return ParamValue::other();
  }
}

}  // namespace

ControllerSpec toControllerSpec(const std::string& name, const XmlRpcValue& params) {
  ControllerSpec spec;
  spec.name = name;
  spec.params = toParamValue(params);
  if (spec.params.kind() != ParamValue::Kind::kDict) {
    throw ControllerError(controllerPrefix(name) + "its parameters must be a dictionary, got " +
                          spec.params.typeName());
  }
  // The type picks the class (controller_manager reads it); the class reads the rest.
  if (const ParamValue* type = spec.params.find("type")) {
    if (type->kind() != ParamValue::Kind::kString) {
      throw ControllerError(controllerPrefix(name) + "type must be a string, got " +
                            type->typeName());
    }
    spec.type = type->asString();
  }
  return spec;
}

std::vector<ControllerSpec> loadControllerSpecs(const ros::NodeHandle& ns,
                                                const std::vector<std::string>& names) {
  std::vector<ControllerSpec> specs;
  for (const std::string& name : names) {
    XmlRpcValue params;
    if (!ns.getParam(name, params)) {
      throw ControllerError(controllerPrefix(name) + "no parameters at " + ns.resolveName(name));
    }
    specs.push_back(toControllerSpec(name, params));
  }
  return specs;
}

ControllerCommandSubscribers::ControllerCommandSubscribers(ros::NodeHandle ns,
                                                           ControllerSet& controllers) {
  for (const auto& c : controllers.controllers()) {
    if (!c->hasCommand()) continue;
    Controller* controller = c.get();
    subscribers_.push_back(ns.subscribe<std_msgs::Float64>(
        controller->name() + "/command", 10,
        [this, controller](const std_msgs::Float64::ConstPtr& msg) { onCommand(controller, msg); }));
  }
}

void ControllerCommandSubscribers::onCommand(Controller* controller,
                                             const std_msgs::Float64::ConstPtr& msg) {
  std::lock_guard<std::mutex> lock(mutex_);
  if (!std::isfinite(msg->data)) {
    // At most one warning a second per controller (a per-call-site throttle would let one
    // controller's warnings hide another's).
    Ignored& ignored = ignored_[controller];
    const ros::WallTime now = ros::WallTime::now();
    if (ignored.last_warning.isZero() || (now - ignored.last_warning).toSec() >= 1.0) {
      std::ostringstream text;
      text << "controller '" << controller->name() << "': ignoring command " << msg->data
           << " (not finite)";
      if (ignored.since_warning > 0) {
        text << "; " << ignored.since_warning << " more ignored since the last warning";
      }
      ROS_WARN_STREAM(text.str());
      ignored.last_warning = now;
      ignored.since_warning = 0;
    } else {
      ++ignored.since_warning;
    }
    return;
  }
  pending_[controller] = msg->data;
}

void ControllerCommandSubscribers::apply() {
  std::map<Controller*, double> pending;
  {
    std::lock_guard<std::mutex> lock(mutex_);
    pending.swap(pending_);
  }
  for (const auto& kv : pending) kv.first->setCommand(kv.second);
}

void ControllerCommandSubscribers::clear() {
  std::lock_guard<std::mutex> lock(mutex_);
  pending_.clear();
}

std::vector<std::string> ControllerCommandSubscribers::topics() const {
  std::vector<std::string> out;
  for (const auto& s : subscribers_) out.push_back(s.getTopic());
  return out;
}

}  // namespace tianracer_control
