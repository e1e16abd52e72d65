#include "tianracer_control/controller_set.h"

#include "tianracer_control/controller_registry.h"

namespace tianracer_control {

Controller& ControllerSet::add(std::unique_ptr<Controller> controller, double time) {
  if (!controller) throw ControllerError("ControllerSet::add: null controller");
  for (const auto& c : controllers_) {
    if (c->name() == controller->name()) {
      throw ControllerError(controllerPrefix(controller->name()) +
                            "a controller of that name is loaded");
    }
    if (controller->joint() != nullptr && c->joint() == controller->joint()) {
      throw ControllerError(controllerPrefix(controller->name()) + "joint '" +
                            controller->joint()->name + "' is already commanded by controller '" +
                            c->name() + "'");
    }
  }
  controller->starting(time);
  controllers_.push_back(std::move(controller));
  return *controllers_.back();
}

Controller& ControllerSet::load(const ControllerSpec& spec,
                                std::map<std::string, JointHandle*>& joints, double time,
                                const WarningSink& warn) {
  return add(builtinControllers().create(spec, joints, warn), time);
}

void ControllerSet::update(double dt) {
  for (auto& c : controllers_) c->update(dt);
}

void ControllerSet::reset(double time) {
  for (auto& c : controllers_) {
    c->reset();
    c->starting(time);
  }
}

Controller* ControllerSet::find(const std::string& name) {
  for (auto& c : controllers_) {
    if (c->name() == name) return c.get();
  }
  return nullptr;
}

const Controller* ControllerSet::find(const std::string& name) const {
  return const_cast<ControllerSet*>(this)->find(name);
}

}  // namespace tianracer_control
