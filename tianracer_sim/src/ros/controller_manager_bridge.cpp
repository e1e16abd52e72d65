#include "tianracer_sim/ros/controller_manager_bridge.h"

#include <sstream>

#include <tianracer_control/ros/controller_adapter.h>

namespace tianracer_sim {

namespace tc = tianracer_control;
namespace cmm = controller_manager_msgs;

namespace {

/// Runs `change` of the controllers: false when it throws ControllerError, whose text is
/// logged as controller_manager logs errors, each on its own line.
template <class Change>
bool logErrors(Change&& change) {
  try {
    change();
  } catch (const tc::ControllerError& e) {
    std::istringstream lines(e.what());
    for (std::string line; std::getline(lines, line);) ROS_ERROR_STREAM(line);
    return false;
  }
  return true;
}

}  // namespace

ControllerManagerBridge::ControllerManagerBridge(ros::NodeHandle robot_nh, std::string control_ns,
                                                 Simulator& sim, ModelId robot,
                                                 std::function<void()> changed)
    : control_ns_(std::move(control_ns)), sim_(sim), robot_(robot), changed_(std::move(changed)) {
  ServiceAdvertiser<ControllerManagerBridge> serve(ros::NodeHandle(robot_nh, "controller_manager"),
                                                   this, &services_);
  serve("list_controllers", &ControllerManagerBridge::onList);
  serve("list_controller_types", &ControllerManagerBridge::onListTypes);
  serve("load_controller", &ControllerManagerBridge::onLoad);
  serve("unload_controller", &ControllerManagerBridge::onUnload);
  serve("switch_controller", &ControllerManagerBridge::onSwitch);
  serve("reload_controller_libraries", &ControllerManagerBridge::onReload);
}

SimRobot& ControllerManagerBridge::robot() const {
  SimRobot* r = sim_.robot(robot_);
  if (!r) throw tc::ControllerError("the robot of this controller manager is no longer in the world");
  return *r;
}

const tc::ControllerSet& ControllerManagerBridge::controllers() const { return robot().controllers; }

bool ControllerManagerBridge::onList(cmm::ListControllers::Request&,
                                     cmm::ListControllers::Response& res) {
  const tc::ControllerSet& set = controllers();
  for (const auto& c : set.controllers()) {
    cmm::ControllerState s;
    s.name = c->name();
    s.type = c->type();
    s.state = tc::toString(set.state(*c));
    for (const tc::ClaimedResources& r : tc::ControllerSet::claimedResources(*c)) {
      cmm::HardwareInterfaceResources m;
      m.hardware_interface = r.hardware_interface;
      m.resources = r.resources;
      s.claimed_resources.push_back(m);
    }
    res.controller.push_back(s);
  }
  return true;
}

bool ControllerManagerBridge::onListTypes(cmm::ListControllerTypes::Request&,
                                          cmm::ListControllerTypes::Response& res) {
  for (const std::string& type : tc::builtinControllers().types()) {
    res.types.push_back(type);
    res.base_classes.push_back("controller_interface::ControllerBase");
  }
  return true;
}

bool ControllerManagerBridge::load(const std::string& name) {
  ros::NodeHandle controller_nh;
  try {
    controller_nh = ros::NodeHandle(ros::NodeHandle(control_ns_), name);
  } catch (const std::exception& e) {
    ROS_ERROR("Exception thrown while constructing nodehandle for controller with name '%s':\n%s",
              name.c_str(), e.what());
    return false;
  }
  XmlRpc::XmlRpcValue params;
  std::string type;
  if (!ros::NodeHandle(control_ns_).getParam(name, params) ||
      params.getType() != XmlRpc::XmlRpcValue::TypeStruct || !controller_nh.getParam("type", type)) {
    ROS_ERROR("Could not load controller '%s' because the type was not specified. Did you load the "
              "controller configuration on the parameter server (namespace: '%s')?",
              name.c_str(), controller_nh.getNamespace().c_str());
    return false;
  }
  return logErrors([&] { sim_.controllerManager().load(robot(), tc::toControllerSpec(name, params)); });
}

bool ControllerManagerBridge::answer(bool ok, uint8_t* res_ok) {
  *res_ok = ok;
  if (ok && changed_) changed_();
  return true;
}

bool ControllerManagerBridge::onLoad(cmm::LoadController::Request& req,
                                     cmm::LoadController::Response& res) {
  return answer(load(req.name), &res.ok);
}

bool ControllerManagerBridge::unload(const std::string& name) {
  return logErrors([&] { sim_.controllerManager().unload(robot(), name); });
}

bool ControllerManagerBridge::onUnload(cmm::UnloadController::Request& req,
                                       cmm::UnloadController::Response& res) {
  return answer(unload(req.name), &res.ok);
}

bool ControllerManagerBridge::switchControllers(const std::vector<std::string>& start,
                                                const std::vector<std::string>& stop,
                                                int strictness) {
  if (strictness == 0) {
    ROS_WARN("Controller Manager: To switch controllers you need to specify a strictness level of "
             "controller_manager_msgs::SwitchController::STRICT (%d) or ::BEST_EFFORT (%d). "
             "Defaulting to ::BEST_EFFORT.",
             cmm::SwitchController::Request::STRICT, cmm::SwitchController::Request::BEST_EFFORT);
  }
  const tc::Strictness s = strictness == cmm::SwitchController::Request::STRICT
                               ? tc::Strictness::kStrict
                               : tc::Strictness::kBestEffort;
  return logErrors([&] { sim_.controllerManager().switchControllers(robot(), start, stop, s); });
}

bool ControllerManagerBridge::onSwitch(cmm::SwitchController::Request& req,
                                       cmm::SwitchController::Response& res) {
  // start_asap and timeout: every joint is ready at once here, so nothing waits.
  return answer(switchControllers(req.start_controllers, req.stop_controllers, req.strictness),
                &res.ok);
}

bool ControllerManagerBridge::onReload(cmm::ReloadControllerLibraries::Request& req,
                                       cmm::ReloadControllerLibraries::Response& res) {
  std::vector<std::string> names;
  for (const auto& c : controllers().controllers()) names.push_back(c->name());
  res.ok = false;
  if (!names.empty() && !req.force_kill) {
    ROS_ERROR("Controller manager: Cannot reload controller libraries because there are still %i "
              "controllers running",
              static_cast<int>(names.size()));
    return true;
  }
  if (!names.empty()) {
    ROS_INFO("Controller manager: Killing all running controllers");
    if (!switchControllers({}, names, cmm::SwitchController::Request::BEST_EFFORT)) {
      ROS_ERROR("Controller manager: Cannot reload controller libraries because failed to stop "
                "running controllers");
      return true;
    }
    for (const std::string& name : names) {
      if (!unload(name)) {
        ROS_ERROR("Controller manager: Cannot reload controller libraries because failed to "
                  "unload controller '%s'",
                  name.c_str());
        if (changed_) changed_();
        return true;
      }
    }
    if (changed_) changed_();
  }
  // The controller types are compiled in: there is nothing to reload.
  ROS_INFO("Controller manager: reloaded controller libraries for 'controller_interface'");
  res.ok = true;
  return true;
}

}  // namespace tianracer_sim
