#include "tianracer_sim/sim/controller_manager.h"

#include <map>
#include <utility>

#include "tianracer_sim/sim/simulation.h"

namespace tianracer_sim {

namespace tc = tianracer_control;

namespace {

std::map<std::string, tc::JointHandle*> jointsOf(SimRobot& robot) {
  std::map<std::string, tc::JointHandle*> joints;
  for (tc::JointHandle& h : robot.handles) joints[h.name] = &h;
  return joints;
}

}  // namespace

ControllerManager::ControllerManager(PhysicsWorld& physics, WarningSink warn,
                                     std::function<void(SimRobot&)> read)
    : physics_(physics), warn_(std::move(warn)), read_(std::move(read)) {}

WarningSink ControllerManager::robotWarnings(const SimRobot& robot) const {
  if (!warn_) return WarningSink();
  return [this, name = robot.name](const std::string& w) { warn_("robot '" + name + "': " + w); };
}

void ControllerManager::attach(SimRobot& robot, const std::vector<tc::ControllerSpec>& specs) {
  std::map<std::string, tc::JointHandle*> joints = jointsOf(robot);
  read_(robot);
  robot.controllers.setRobotDescription(robot.model.urdf.get());
  const WarningSink warn = robotWarnings(robot);
  for (const tc::ControllerSpec& spec : specs) robot.controllers.load(spec, joints, physics_.time(), warn);
  robot.claimed.assign(robot.handles.size(), false);
  updateClaims(robot);
}

tc::Controller& ControllerManager::load(SimRobot& robot, const tc::ControllerSpec& spec) {
  std::map<std::string, tc::JointHandle*> joints = jointsOf(robot);
  return robot.controllers.loadController(spec, joints, robotWarnings(robot));
}

void ControllerManager::unload(SimRobot& robot, const std::string& name) {
  robot.controllers.unloadController(name);
  updateClaims(robot);
}

void ControllerManager::switchControllers(SimRobot& robot, const std::vector<std::string>& start,
                                          const std::vector<std::string>& stop,
                                          tc::Strictness strictness) {
  read_(robot);  // a controller starting holds the current position
  robot.controllers.switchControllers(start, stop, strictness, physics_.time());
  updateClaims(robot);
}

bool ControllerManager::setCommand(SimRobot& robot, const std::string& controller, double value) {
  tc::Controller* c = robot.controllers.find(controller);
  return c && c->hasCommand() && c->setCommand(value);
}

void ControllerManager::update(SimRobot& robot) {
  robot.controllers.update(robot.control_every * physics_.dt(), physics_.time());
}

void ControllerManager::restart(SimRobot& robot) {
  for (tc::JointHandle& h : robot.handles) h.command = 0.0;
  read_(robot);
  robot.controllers.reset(physics_.time());
}

void ControllerManager::updateClaims(SimRobot& robot) {
  PhysicsRobot& pr = physics_.robot(robot.id);
  for (size_t k = 0; k < robot.handles.size(); ++k) {
    bool claimed = false;
    for (const auto& c : robot.controllers.controllers()) {
      if (!robot.controllers.isRunning(*c)) continue;
      for (const tc::JointHandle* j : c->claimedJoints()) claimed = claimed || j == &robot.handles[k];
    }
    if (robot.claimed[k] && !claimed && robot.handle_joint[k] >= 0)
      pr.clearJointCommand(robot.handle_joint[k]);
    robot.claimed[k] = claimed;
  }
}

}  // namespace tianracer_sim
