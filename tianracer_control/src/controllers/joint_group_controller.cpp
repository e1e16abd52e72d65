#include "tianracer_control/controllers/joint_group_controller.h"

#include <cmath>
#include <sstream>

#include "tianracer_control/pid_params.h"

namespace tianracer_control {

namespace {

// forward_joint_group_command_controller.h's init(): "joints", a non-empty list.
std::vector<JointHandle*> claimJoints(ControllerContext& context, JointHandle::Interface needs) {
  ControllerParams& params = context.params;
  const std::optional<std::vector<std::string>> names = params.textList("joints");
  if (!names) {
    throw ControllerError(params.prefix() + "Failed to getParam 'joints' (" + params.type() +
                          " needs a list of joints)");
  }
  if (names->empty()) throw ControllerError(params.prefix() + "List of joint names is empty.");
  std::vector<JointHandle*> joints;
  for (const std::string& name : *names) {
    JointHandle* j = findJoint(context, name, needs);
    for (const JointHandle* other : joints) {
      if (other == j) {
        throw ControllerError(params.prefix() + "joint '" + name + "' is listed twice in joints");
      }
    }
    joints.push_back(j);
  }
  return joints;
}

double positionError(const JointHandle& j, double target) {
  return j.continuous ? shortestAngularDistance(j.position, target) : target - j.position;
}

}  // namespace

template <JointHandle::Interface I>
std::unique_ptr<Controller> JointGroupController::create(ControllerContext& context) {
  return std::make_unique<JointGroupController>(context.params.name(), context.params.type(),
                                                claimJoints(context, I), std::vector<Pid>());
}

template std::unique_ptr<Controller> JointGroupController::create<JointHandle::Interface::kEffort>(
    ControllerContext&);
template std::unique_ptr<Controller> JointGroupController::create<
    JointHandle::Interface::kVelocity>(ControllerContext&);
template std::unique_ptr<Controller> JointGroupController::create<
    JointHandle::Interface::kPosition>(ControllerContext&);

std::unique_ptr<Controller> JointGroupController::createEffortPosition(ControllerContext& context) {
  std::vector<JointHandle*> joints = claimJoints(context, JointHandle::Interface::kEffort);
  std::vector<Pid> pids;
  for (const JointHandle* j : joints) {
    pids.emplace_back(readPidGains(context.params, context.warn, j->name + "/pid"));
  }
  return std::make_unique<JointGroupController>(context.params.name(), context.params.type(),
                                                std::move(joints), std::move(pids));
}

JointGroupController::JointGroupController(std::string name, std::string type,
                                           std::vector<JointHandle*> joints, std::vector<Pid> pids)
    : Controller(std::move(name), std::move(type)),
      joints_(std::move(joints)),
      pids_(std::move(pids)),
      commands_(joints_.size(), 0.0) {}

std::vector<const JointHandle*> JointGroupController::claimedJoints() const {
  return {joints_.begin(), joints_.end()};
}

bool JointGroupController::positionTargets() const {
  return !pids_.empty() || joints_.front()->interface == JointHandle::Interface::kPosition;
}

double JointGroupController::clamp(const JointHandle& j, double value) const {
  // Only effort_controllers/JointGroupPositionController clamps its targets to the position
  // limits (its enforceJointLimits); the forwarding groups pass commands on as they are.
  return pids_.empty() ? value : clampToPositionLimits(j, value);
}

void JointGroupController::starting(double) {
  for (std::size_t i = 0; i < joints_.size(); ++i) {
    commands_[i] = positionTargets() ? clamp(*joints_[i], joints_[i]->position) : 0.0;
  }
  for (Pid& pid : pids_) pid.reset();
}

void JointGroupController::reset() {
  for (Pid& pid : pids_) pid.reset();
}

void JointGroupController::update(double dt) {
  for (std::size_t i = 0; i < joints_.size(); ++i) {
    JointHandle& j = *joints_[i];
    if (pids_.empty()) {
      j.command = commands_[i];
    } else {
      j.command = pids_[i].computeCommand(positionError(j, commands_[i]), dt);
    }
  }
}

std::string JointGroupController::setCommands(const std::vector<double>& values) {
  if (values.size() != joints_.size()) {
    std::ostringstream os;
    os << "Dimension of command (" << values.size() << ") does not match number of joints ("
       << joints_.size() << ")! Not executing!";
    return os.str();
  }
  for (std::size_t i = 0; i < values.size(); ++i) {
    if (!std::isfinite(values[i])) {
      std::ostringstream os;
      os << "command " << i << " (joint '" << joints_[i]->name << "') is " << values[i]
         << ", not finite: not executing";
      return os.str();
    }
  }
  for (std::size_t i = 0; i < values.size(); ++i) commands_[i] = clamp(*joints_[i], values[i]);
  return "";
}

std::unique_ptr<Controller> VelocityJointPositionController::create(ControllerContext& context) {
  JointHandle* joint = claimJoint(context, JointHandle::Interface::kVelocity);
  const Pid pid(readPidGains(context.params, context.warn));
  return std::make_unique<VelocityJointPositionController>(context.params.name(), joint, pid);
}

VelocityJointPositionController::VelocityJointPositionController(std::string name,
                                                                 JointHandle* joint, const Pid& pid)
    : SingleJointController(std::move(name), kType, joint), pid_(pid) {}

void VelocityJointPositionController::starting(double) {
  command_ = clampToPositionLimits(*joint_, joint_->position);
  pid_.reset();
}

void VelocityJointPositionController::update(double dt) {
  const double error = positionError(*joint_, command_);
  const double velocity = pid_.computeCommand(error, dt);
  joint_->command = velocity;  // upstream sets the PID's output; the hardware limits it
  recordPidState(command_, joint_->position, joint_->velocity, error, dt, velocity, pid_.gains());
}

bool VelocityJointPositionController::setCommand(double value) {
  if (!std::isfinite(value)) return false;
  command_ = clampToPositionLimits(*joint_, value);
  return true;
}

}  // namespace tianracer_control
