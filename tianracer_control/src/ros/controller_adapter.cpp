#include "tianracer_control/ros/controller_adapter.h"

#include <cmath>
#include <sstream>

#include <ros/console.h>

namespace tianracer_control {

namespace {

using XmlRpc::XmlRpcValue;

const char* typeName(const XmlRpcValue& v) {
  switch (v.getType()) {
    case XmlRpcValue::TypeBoolean:
      return "a bool";
    case XmlRpcValue::TypeInt:
      return "an int";
    case XmlRpcValue::TypeDouble:
      return "a double";
    case XmlRpcValue::TypeString:
      return "a string";
    case XmlRpcValue::TypeArray:
      return "a list";
    case XmlRpcValue::TypeStruct:
      return "a dictionary";
    default:
      return "an unsupported value";
  }
}

std::string prefix(const std::string& name) { return "controller '" + name + "': "; }

// XmlRpcValue's conversions are non-const: the helpers read from a copy.
double number(const std::string& name, const std::string& key, XmlRpcValue v) {
  if (v.getType() == XmlRpcValue::TypeDouble) return static_cast<double>(v);
  if (v.getType() == XmlRpcValue::TypeInt) return static_cast<int>(v);
  throw ControllerError(prefix(name) + key + " must be a number, got " + typeName(v));
}

std::string text(const std::string& name, const std::string& key, XmlRpcValue v) {
  if (v.getType() == XmlRpcValue::TypeString) return static_cast<std::string>(v);
  throw ControllerError(prefix(name) + key + " must be a string, got " + typeName(v));
}

bool boolean(const std::string& name, const std::string& key, XmlRpcValue v) {
  if (v.getType() == XmlRpcValue::TypeBoolean) return static_cast<bool>(v);
  throw ControllerError(prefix(name) + key + " must be true or false, got " + typeName(v));
}

}  // namespace

ControllerSpec toControllerSpec(const std::string& name, const XmlRpcValue& params) {
  if (params.getType() != XmlRpcValue::TypeStruct) {
    throw ControllerError(prefix(name) + "its parameters must be a dictionary, got " +
                          typeName(params));
  }
  ControllerSpec spec;
  spec.name = name;
  for (auto it = params.begin(); it != params.end(); ++it) {
    const std::string& key = it->first;
    const XmlRpcValue& value = it->second;
    spec.keys.push_back(key);
    if (key == "type") {
      spec.type = text(name, key, value);
    } else if (key == "joint") {
      spec.joint = text(name, key, value);
    } else if (key == "publish_rate") {
      spec.publish_rate = number(name, key, value);
    } else if (key == "pid") {
      if (value.getType() != XmlRpcValue::TypeStruct) {
        throw ControllerError(prefix(name) + "pid must be a dictionary, got " + typeName(value));
      }
      PidParams pid;
      for (auto p = value.begin(); p != value.end(); ++p) {
        const std::string sub = "pid/" + p->first;
        spec.keys.push_back(sub);
        const XmlRpcValue& v = p->second;
        if (p->first == "p") pid.p = number(name, sub, v);
        else if (p->first == "i") pid.i = number(name, sub, v);
        else if (p->first == "d") pid.d = number(name, sub, v);
        else if (p->first == "i_clamp") pid.i_clamp = number(name, sub, v);
        else if (p->first == "i_clamp_min") pid.i_clamp_min = number(name, sub, v);
        else if (p->first == "i_clamp_max") pid.i_clamp_max = number(name, sub, v);
        else if (p->first == "antiwindup") pid.antiwindup = boolean(name, sub, v);
        // other keys stay in spec.keys and are reported by makeController()
      }
      spec.pid = pid;
    }
  }
  return spec;
}

std::vector<ControllerSpec> loadControllerSpecs(const ros::NodeHandle& ns,
                                                const std::vector<std::string>& names) {
  std::vector<ControllerSpec> specs;
  for (const std::string& name : names) {
    XmlRpcValue params;
    if (!ns.getParam(name, params)) {
      throw ControllerError(prefix(name) + "no parameters at " + ns.resolveName(name));
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
