#include "tianracer_control/ros/controller_adapter.h"

namespace tianracer_control {

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
                                                           ControllerSet& controllers,
                                                           ControllerCommandSubscribers* previous) {
  for (const auto& c : controllers.controllers()) {
    std::unique_ptr<ControllerRosSide> side;
    for (std::size_t i = 0; previous && i < previous->owners_.size(); ++i) {
      if (previous->owners_[i] == c.get() && previous->sides_[i]) side.swap(previous->sides_[i]);
    }
    if (!side) {
      const RosSideFactory factory = findRosSide(c->type());
      if (!factory) continue;
      RosSideContext context{ns, ros::NodeHandle(ns, c->name()), *c, controllers};
      side = factory(context);
    }
    sides_.push_back(std::move(side));
    owners_.push_back(c.get());
  }
}

ControllerCommandSubscribers::~ControllerCommandSubscribers() = default;

void ControllerCommandSubscribers::apply() {
  for (const auto& side : sides_) side->apply();
}

void ControllerCommandSubscribers::publish(double t) {
  for (const auto& side : sides_) side->publish(t);
}

void ControllerCommandSubscribers::clear() {
  for (const auto& side : sides_) side->clear();
}

std::vector<std::string> ControllerCommandSubscribers::topics() const {
  std::vector<std::string> out;
  for (const auto& side : sides_) {
    for (const std::string& t : side->commandTopics()) out.push_back(t);
  }
  return out;
}

}  // namespace tianracer_control
