#include "tianracer_control/controllers/gripper_action_controller.h"

#include <algorithm>
#include <cmath>
#include <sstream>

#include "tianracer_control/pid_params.h"

namespace tianracer_control {

namespace {

// controller_nh_.param<double>(key, default): here a value that is no number, or not finite,
// fails the load.
double readFinite(ControllerParams& params, const std::string& key, double fallback) {
  const std::optional<double> v = params.number(key);
  if (!v) return fallback;
  if (!std::isfinite(*v)) {
    std::ostringstream os;
    os << params.prefix() << key << " is " << *v << ", must be finite";
    throw ControllerError(os.str());
  }
  return *v;
}

}  // namespace

template <JointHandle::Interface I>
std::unique_ptr<Controller> GripperActionController::create(ControllerContext& context) {
  ControllerParams& params = context.params;
  Options options;
  options.action_monitor_rate = readFinite(params, "action_monitor_rate", 20.0);
  if (options.action_monitor_rate <= 0.0) {
    std::ostringstream os;
    os << params.prefix() << "action_monitor_rate is " << options.action_monitor_rate
       << ", must be > 0 [Hz]";
    throw ControllerError(os.str());
  }
  const std::optional<std::string> joint_name = params.text("joint");
  if (!joint_name || joint_name->empty()) {
    throw ControllerError(params.prefix() + "Could not find joint name on param server");
  }
  JointHandle* joint = findJoint(context, *joint_name, I);
  options.goal_tolerance = std::fabs(readFinite(params, "goal_tolerance", 0.01));
  options.max_effort = std::fabs(readFinite(params, "max_effort", 0.0));
  options.stall_velocity_threshold = readFinite(params, "stall_velocity_threshold", 0.001);
  options.stall_timeout = readFinite(params, "stall_timeout", 1.0);
  std::optional<Pid> pid;
  if (I == JointHandle::Interface::kEffort) {
    const std::string ns = "gains/" + *joint_name;
    if (!params.value(ns)) {
      throw ControllerError(params.prefix() +
                            "Failed to initialize PID gains from ROS parameter server. (no " + ns +
                            ")");
    }
    pid.emplace(readPidGains(params, context.warn, ns));
  }
  return std::make_unique<GripperActionController>(params.name(), params.type(), joint, options,
                                                   pid);
}

template std::unique_ptr<Controller>
GripperActionController::create<JointHandle::Interface::kPosition>(ControllerContext&);
template std::unique_ptr<Controller>
GripperActionController::create<JointHandle::Interface::kEffort>(ControllerContext&);

GripperActionController::GripperActionController(std::string name, std::string type,
                                                 JointHandle* joint, const Options& options,
                                                 std::optional<Pid> pid)
    : SingleJointController(std::move(name), std::move(type), joint),
      options_(options),
      pid_(std::move(pid)) {}

void GripperActionController::starting(double time) {
  finish(GoalEvent::Kind::kCanceled, false, false);  // stopping(): preemptActiveGoal
  target_ = joint_->position;
  max_effort_ = options_.max_effort;
  if (pid_) {
    pid_->reset();
    joint_->command = 0.0;
  }
  last_movement_time_ = time;
  running_ = true;
}

void GripperActionController::reset() {
  if (pid_) pid_->reset();
}

void GripperActionController::finish(GoalEvent::Kind kind, bool stalled, bool reached) {
  if (active_goal_ == 0) return;
  GoalEvent e;
  e.goal = active_goal_;
  e.kind = kind;
  e.position = joint_->position;
  e.effort = computed_command_;
  e.stalled = stalled;
  e.reached_goal = reached;
  events_.push_back(e);
  active_goal_ = 0;
}

std::vector<GripperActionController::GoalEvent> GripperActionController::takeGoalEvents() {
  std::vector<GoalEvent> out;
  out.swap(events_);
  return out;
}

void GripperActionController::checkForSuccess(double time, double error_position) {
  if (active_goal_ == 0) return;
  if (std::fabs(error_position) < options_.goal_tolerance) {
    finish(GoalEvent::Kind::kSucceeded, false, true);
  } else if (std::fabs(joint_->velocity) > options_.stall_velocity_threshold) {
    last_movement_time_ = time;
  } else if (time - last_movement_time_ > options_.stall_timeout) {
    finish(GoalEvent::Kind::kAborted, true, false);
  }
}

void GripperActionController::update(double dt) {
  if (!running_) starting(now());
  const double error_position = target_ - joint_->position;
  const double error_velocity = -joint_->velocity;
  checkForSuccess(now(), error_position);
  if (pid_) {
    const double m = std::fabs(max_effort_);
    computed_command_ = std::clamp(pid_->computeCommand(error_position, error_velocity, dt), -m, m);
    joint_->command = computed_command_;
  } else {
    joint_->command = target_;  // upstream's position adapter; the hardware enforces the limits
    computed_command_ = max_effort_;
  }
}

std::string GripperActionController::startGoal(GoalId goal, double position, double max_effort) {
  if (!running_) return "Can't accept new action goals. Controller is not running.";
  if (!std::isfinite(position) || !std::isfinite(max_effort)) {
    // upstream takes it and commands NaN
    std::ostringstream os;
    os << "Gripper command (position " << position << ", max_effort " << max_effort
       << ") holds a non-finite value: rejected";
    return os.str();
  }
  finish(GoalEvent::Kind::kCanceled, false, false);  // preemptActiveGoal
  active_goal_ = goal;
  target_ = position;
  max_effort_ = max_effort;
  last_movement_time_ = now();
  return "";
}

bool GripperActionController::cancelGoal(GoalId goal) {
  if (goal == 0 || goal != active_goal_) return false;
  target_ = joint_->position;  // setHoldPosition
  max_effort_ = options_.max_effort;
  finish(GoalEvent::Kind::kCanceled, false, false);
  return true;
}

}  // namespace tianracer_control
