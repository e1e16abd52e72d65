#include "tianracer_control/controller_set.h"

#include <algorithm>
#include <set>

namespace tianracer_control {

const char* toString(ControllerState state) {
  static const char* const kNames[] = {"initialized", "running", "stopped"};  // by ControllerState
  return kNames[static_cast<int>(state)];
}

Controller& ControllerSet::add(std::unique_ptr<Controller> controller, double time) {
  if (!controller) throw ControllerError("ControllerSet::add: null controller");
  for (const auto& c : controllers_) {
    if (c->name() == controller->name()) {
      throw ControllerError(controllerPrefix(controller->name()) +
                            "a controller of that name is loaded");
    }
    for (const JointHandle* mine : controller->claimedJoints()) {
      for (const JointHandle* theirs : c->claimedJoints()) {
        if (mine != theirs) continue;
        throw ControllerError(controllerPrefix(controller->name()) + "joint '" + mine->name +
                              "' is already commanded by controller '" + c->name() + "'");
      }
    }
  }
  startController(*controller, time);
  controllers_.push_back(std::move(controller));
  states_.push_back(ControllerState::kRunning);
  return *controllers_.back();
}

Controller& ControllerSet::load(const ControllerSpec& spec,
                                std::map<std::string, JointHandle*>& joints, double time,
                                const WarningSink& warn) {
  return add(builtinControllers().create(spec, joints, warn, description_), time);
}

Controller& ControllerSet::loadController(const ControllerSpec& spec,
                                          std::map<std::string, JointHandle*>& joints,
                                          const WarningSink& warn,
                                          const ControllerRegistry& registry) {
  const std::string& name = spec.name;
  if (find(name)) {
    throw ControllerError("A controller named '" + name +
                          "' was already loaded inside the controller manager");
  }
  if (spec.type.empty()) {
    throw ControllerError("Could not load controller '" + name +
                          "' because the type was not specified.");
  }
  if (!registry.has(spec.type)) {
    throw ControllerError("Could not load controller '" + name + "' because controller type '" +
                          spec.type + "' does not exist.\nUse 'rosservice call "
                          "controller_manager/list_controller_types' to get the available types");
  }
  std::unique_ptr<Controller> controller;
  try {
    controller = registry.create(spec, joints, warn, description_);
  } catch (const ControllerError& e) {
    throw ControllerError(std::string(e.what()) + "\nInitializing controller '" + name +
                          "' failed");
  }
  controllers_.push_back(std::move(controller));
  states_.push_back(ControllerState::kInitialized);
  return *controllers_.back();
}

void ControllerSet::unloadController(const std::string& name) {
  const Controller* c = find(name);
  if (!c) {
    throw ControllerError("Could not unload controller with name '" + name +
                          "' because no controller with this name exists");
  }
  const std::size_t i = indexOf(*c);
  if (states_[i] == ControllerState::kRunning) {
    throw ControllerError("Could not unload controller with name '" + name +
                          "' because it is still running");
  }
  controllers_.erase(controllers_.begin() + static_cast<std::ptrdiff_t>(i));
  states_.erase(states_.begin() + static_cast<std::ptrdiff_t>(i));
}

void ControllerSet::switchControllers(const std::vector<std::string>& start,
                                      const std::vector<std::string>& stop,
                                      Strictness strictness, double time) {
  const bool strict = strictness == Strictness::kStrict;
  // The named controllers; an unknown name is an error when strict, else skipped.
  const auto named = [&](const std::vector<std::string>& names, const char* verb) {
    std::set<const Controller*> found;
    for (const std::string& name : names) {
      const Controller* c = find(name);
      if (!c && strict) {
        throw ControllerError(std::string("Could not ") + verb + " controller with name '" + name +
                              "' because no controller with this name exists");
      }
      if (c) found.insert(c);
    }
    return found;
  };
  const std::set<const Controller*> stop_set = named(stop, "stop");
  const std::set<const Controller*> start_set = named(start, "start");
  // What runs afterwards, with controller_manager's checks per controller.
  std::vector<bool> runs(controllers_.size(), false), stops(controllers_.size(), false),
      starts(controllers_.size(), false);
  for (std::size_t i = 0; i < controllers_.size(); ++i) {
    const Controller* c = controllers_[i].get();
    const bool running = states_[i] == ControllerState::kRunning;
    bool in_stop = stop_set.count(c) > 0, in_start = start_set.count(c) > 0;
    if (!running && in_stop) {
      if (strict) {
        throw ControllerError("Could not stop controller '" + c->name() +
                              "' since it is not running");
      }
      in_stop = false;
    }
    if (running && !in_stop && in_start) {
      if (strict) throw ControllerError("Controller '" + c->name() + "' is already running");
      in_start = false;
    }
    if (in_stop && in_start) {  // sic: controller_manager's text
      throw ControllerError("Could no start or stop controller '" + c->name() +
                            "' because of conflicting switching command");
    }
    stops[i] = running && in_stop;
    starts[i] = !running && in_start;
    runs[i] = (running && !in_stop) || in_start;
  }
  // RobotHW::checkForConflict: no joint claimed by two running controllers.
  std::map<std::string, std::vector<std::string>> claims;  // joint -> controllers
  for (std::size_t i = 0; i < controllers_.size(); ++i) {
    if (!runs[i]) continue;
    for (const ClaimedResources& r : claimedResources(*controllers_[i])) {
      for (const std::string& joint : r.resources) claims[joint].push_back(controllers_[i]->name());
    }
  }
  std::string conflicts;
  for (const auto& [joint, names] : claims) {
    if (names.size() < 2) continue;
    std::string list;
    for (const std::string& n : names) list += n + ", ";
    conflicts += "Resource conflict on [" + joint + "].  Controllers = [" + list + "]\n";
  }
  if (!conflicts.empty()) {
    throw ControllerError(conflicts + "Could not switch controllers, due to resource conflict");
  }
  for (std::size_t i = 0; i < controllers_.size(); ++i) {
    if (stops[i]) states_[i] = ControllerState::kStopped;
  }
  for (std::size_t i = 0; i < controllers_.size(); ++i) {
    if (!starts[i]) continue;
    startController(*controllers_[i], time);
    states_[i] = ControllerState::kRunning;
  }
}

void ControllerSet::startController(Controller& controller, double time) {
  controller.now_ = time;
  clock_ = time;
  controller.starting(time);
}

void ControllerSet::update(double dt, double time) {
  clock_ = time;
  for (std::size_t i = 0; i < controllers_.size(); ++i) {
    if (states_[i] != ControllerState::kRunning) continue;
    controllers_[i]->now_ = time;
    controllers_[i]->update(dt);
  }
}

void ControllerSet::reset(double time) {
  clock_ = time;
  for (std::size_t i = 0; i < controllers_.size(); ++i) {
    controllers_[i]->reset();
    if (states_[i] == ControllerState::kRunning) startController(*controllers_[i], time);
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

std::size_t ControllerSet::indexOf(const Controller& controller) const {
  for (std::size_t i = 0; i < controllers_.size(); ++i) {
    if (controllers_[i].get() == &controller) return i;
  }
  throw ControllerError(controllerPrefix(controller.name()) + "not in this set");
}

ControllerState ControllerSet::state(const Controller& controller) const {
  return states_[indexOf(controller)];
}

std::vector<ClaimedResources> ControllerSet::claimedResources(const Controller& controller) {
  const std::vector<const JointHandle*> joints = controller.claimedJoints();
  if (joints.empty()) return {{"hardware_interface::JointStateInterface", {}}};
  std::vector<ClaimedResources> out;
  for (const JointHandle* joint : joints) {
    const std::string iface = std::string("hardware_interface::") + toString(joint->interface);
    auto it = std::find_if(out.begin(), out.end(),
                           [&](const ClaimedResources& r) { return r.hardware_interface == iface; });
    if (it == out.end()) it = out.insert(out.end(), ClaimedResources{iface, {}});
    it->resources.push_back(joint->name);
  }
  return out;
}

}  // namespace tianracer_control
