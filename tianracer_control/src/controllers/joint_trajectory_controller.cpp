#include "tianracer_control/controllers/joint_trajectory_controller.h"

#include <algorithm>
#include <cmath>

#include "tianracer_control/pid_params.h"

namespace tianracer_control {

using trajectory::GoalCheck;
using trajectory::GoalId;
using trajectory::JointTrajectoryCommand;
using trajectory::State;

namespace {

// FollowJointTrajectoryResult's error codes.
constexpr int kInvalidGoal = -1;
constexpr int kInvalidJoints = -2;

// init()'s getStrings(controller_nh, "joints") and hw->getHandle().
std::vector<JointHandle*> claimTrajectoryJoints(ControllerContext& context, JointHandle::Interface needs) {
  ControllerParams& params = context.params;
  const ParamValue* value = params.value("joints");
  if (!value) {
    throw ControllerError(params.prefix() + "Could not find 'joints' parameter (namespace: " +
                          params.name() + ").");
  }
  if (value->kind() != ParamValue::Kind::kList) {
    throw ControllerError(params.prefix() + "The 'joints' parameter is not an array (namespace: " +
                          params.name() + ").");
  }
  for (const ParamValue& item : value->items()) {
    if (item.kind() != ParamValue::Kind::kString) {
      throw ControllerError(params.prefix() +
                            "The 'joints' parameter contains a non-string element (namespace: " +
                            params.name() + ").");
    }
  }
  const std::vector<std::string> names = params.textList("joints").value();
  if (names.empty()) {
    // upstream: init() returns false without a word for an empty list
    throw ControllerError(params.prefix() + "The 'joints' parameter is an empty list");
  }
  std::vector<JointHandle*> joints;
  for (const std::string& name : names) {
    JointHandle* j = findJoint(context, name, needs);
    if (std::find(joints.begin(), joints.end(), j) != joints.end()) {
      throw ControllerError(params.prefix() + "joint '" + name + "' is listed twice in joints");
    }
    joints.push_back(j);
  }
  return joints;
}

}  // namespace

template <JointHandle::Interface I>
std::unique_ptr<Controller> JointTrajectoryController::create(ControllerContext& context) {
  ControllerParams& params = context.params;
  std::vector<JointHandle*> joints = claimTrajectoryJoints(context, I);
  std::vector<std::string> names;
  for (const JointHandle* j : joints) names.push_back(j->name);
  trajectory::TrajectoryControllerOptions options =
      trajectory::readTrajectoryControllerOptions(params, names);
  std::vector<Pid> pids;
  std::vector<double> velocity_ff;
  if (I != JointHandle::Interface::kPosition) {
    // ClosedLoopHardwareInterfaceAdapter::init
    for (const std::string& name : names) {
      const std::string ns = "gains/" + name;
      if (!params.value(ns)) {
        throw ControllerError(params.prefix() +
                              "Failed to initialize PID gains from ROS parameter server. (no " +
                              ns + ")");
      }
      pids.emplace_back(readPidGains(params, context.warn, ns));
      const std::optional<double> ff = params.number("velocity_ff/" + name);
      if (ff && !std::isfinite(*ff)) {
        throw ControllerError(params.prefix() + "velocity_ff/" + name + " must be finite");
      }
      velocity_ff.push_back(ff.value_or(0.0));
    }
  }
  return std::make_unique<JointTrajectoryController>(params.name(), params.type(),
                                                     std::move(joints), std::move(options),
                                                     std::move(pids), std::move(velocity_ff));
}

template std::unique_ptr<Controller>
JointTrajectoryController::create<JointHandle::Interface::kPosition>(ControllerContext&);
template std::unique_ptr<Controller>
JointTrajectoryController::create<JointHandle::Interface::kVelocity>(ControllerContext&);
template std::unique_ptr<Controller>
JointTrajectoryController::create<JointHandle::Interface::kEffort>(ControllerContext&);

JointTrajectoryController::JointTrajectoryController(
    std::string name, std::string type, std::vector<JointHandle*> joints,
    trajectory::TrajectoryControllerOptions options, std::vector<Pid> pids,
    std::vector<double> velocity_ff)
    : Controller(std::move(name), std::move(type)),
      joints_(std::move(joints)),
      options_(std::move(options)),
      pids_(std::move(pids)),
      velocity_ff_(std::move(velocity_ff)),
      desired_(joints_.size()),
      current_(joints_.size()),
      error_(joints_.size()),
      done_(joints_.size(), false) {
  for (const JointHandle* j : joints_) {
    joint_names_.push_back(j->name);
    wraparound_.push_back(j->continuous);
  }
}

std::vector<const JointHandle*> JointTrajectoryController::claimedJoints() const {
  return {joints_.begin(), joints_.end()};
}

void JointTrajectoryController::starting(double time) {
  preemptActiveGoal();  // stopping() of the previous run
  time_ = time;
  period_ = 0.0;
  uptime_ = 0.0;
  for (std::size_t i = 0; i < joints_.size(); ++i) {
    desired_.position[i] = joints_[i]->position;
    desired_.velocity[i] = joints_[i]->velocity;
    desired_.acceleration[i] = 0.0;
  }
  setHold(0);
  last_state_publish_ = 0.0;
  state_due_ = false;
  // the adapters' starting(): PIDs reset and 0 for the closed loop, the position for position
  for (Pid& pid : pids_) pid.reset();
  for (JointHandle* j : joints_) {
    j->command = j->interface == JointHandle::Interface::kPosition ? j->position : 0.0;
  }
  running_ = true;
}

void JointTrajectoryController::reset() {
  for (Pid& pid : pids_) pid.reset();
}

void JointTrajectoryController::setHold(GoalId goal) {
  if (options_.stop_trajectory_duration == 0.0) {
    std::vector<double> positions;
    for (const JointHandle* j : joints_) positions.push_back(j->position);
    trajectory_ = trajectory::holdTrajectory(uptime_, positions, goal);
    ++trajectory_version_;
  } else {
    State from(joints_.size());
    from.position = desired_.position;
    from.velocity = desired_.velocity;
    trajectory_ = trajectory::stopTrajectory(uptime_, options_.stop_trajectory_duration, from, goal);
    ++trajectory_version_;
  }
}

void JointTrajectoryController::finishGoal(GoalEvent::Kind kind, int code,
                                           const std::string& text) {
  if (active_goal_ == 0) return;
  events_.push_back(GoalEvent{active_goal_, kind, code, text});
  active_goal_ = 0;
  std::fill(done_.begin(), done_.end(), false);
}

void JointTrajectoryController::preemptActiveGoal() {
  finishGoal(GoalEvent::Kind::kCanceled, 0, "");
}

std::vector<JointTrajectoryController::GoalEvent> JointTrajectoryController::takeGoalEvents() {
  std::vector<GoalEvent> out;
  out.swap(events_);
  return out;
}

void JointTrajectoryController::updateStates() {
  State joint_state;
  for (std::size_t i = 0; i < joints_.size(); ++i) {
    const auto& segments = trajectory_[i];
    const auto segment = trajectory::sampleSegments(segments, uptime_, joint_state);
    current_.position[i] = joints_[i]->position;
    current_.velocity[i] = joints_[i]->velocity;
    if (!joint_state.position.empty()) {
      desired_.position[i] = joint_state.position[0];
      desired_.velocity[i] = joint_state.velocity[0];
      desired_.acceleration[i] = joint_state.acceleration[0];
    }
    if (i == 0 && segment != segments.end()) {
      current_.time_from_start = uptime_ - segment->startTime() + segment->timeFromStart();
      desired_.time_from_start = segment->timeFromStart();
      error_.time_from_start = desired_.time_from_start - current_.time_from_start;
    }
  }
  error_ = trajectory::stateError(desired_, current_);
  error_.time_from_start = desired_.time_from_start - current_.time_from_start;
}

void JointTrajectoryController::update(double dt) {
  if (!running_) starting(now());
  time_ = now();
  period_ = dt;
  uptime_ += dt;
  updateStates();

  if (active_goal_ != 0) {
    const GoalCheck check =
        trajectory::checkGoal(trajectory_, uptime_, error_, active_goal_, joint_names_, done_);
    switch (check.outcome) {
      case GoalCheck::Outcome::kSucceeded:
        finishGoal(GoalEvent::Kind::kSucceeded, 0, "");
        break;
      case GoalCheck::Outcome::kPathToleranceViolated:
      case GoalCheck::Outcome::kGoalToleranceViolated:
        finishGoal(GoalEvent::Kind::kAborted, check.error_code, check.error_string);
        break;
      case GoalCheck::Outcome::kRunning:
        break;
    }
  }

  const double state_period = 1.0 / options_.state_publish_rate;  // publishState
  if (last_state_publish_ + state_period < uptime_) {
    last_state_publish_ += state_period;
    state_due_ = true;
  }

  // hardware_interface_adapter.h
  for (std::size_t i = 0; i < joints_.size(); ++i) {
    JointHandle& j = *joints_[i];
    switch (j.interface) {
      case JointHandle::Interface::kPosition:
        j.command = desired_.position[i];  // the hardware enforces the joint's limits
        break;
      case JointHandle::Interface::kVelocity:
      case JointHandle::Interface::kEffort: {
        j.command = desired_.velocity[i] * velocity_ff_[i] +
                    pids_[i].computeCommand(error_.position[i], error_.velocity[i], dt);
        break;
      }
    }
  }
}

bool JointTrajectoryController::takeStateDue() {
  const bool due = state_due_;
  state_due_ = false;
  return due;
}

JointTrajectoryController::CommandResult JointTrajectoryController::updateTrajectoryCommand(
    const JointTrajectoryCommand& command, GoalId goal,
    const trajectory::GoalTolerances* tolerances) {
  CommandResult result;
  if (!running_) {
    result.error = "Can't accept new commands. Controller is not running.";
    return result;
  }
  if (command.points.empty()) {  // hold the current position
    setHold(goal);
    return result;
  }
  trajectory::InitOptions options;
  options.current_trajectory = &trajectory_;
  options.joint_names = &joint_names_;
  options.angle_wraparound = &wraparound_;
  options.goal = goal;
  options.goal_tolerances = tolerances;
  options.default_tolerances = &options_.default_tolerances;
  options.other_time_base = uptime_ + period_;  // uptime of the next update
  options.allow_partial_joints_goal = options_.allow_partial_joints_goal;
  trajectory::InitResult init = trajectory::initJointTrajectory(command, time_ + period_, options);
  result.warnings = std::move(init.warnings);
  if (!init.ok()) {
    result.error = init.error;
    return result;
  }
  if (init.trajectory.empty()) {
    result.error = "Trajectory message gave an empty trajectory.";
    return result;
  }
  trajectory_ = std::move(init.trajectory);
  ++trajectory_version_;
  return result;
}

JointTrajectoryController::CommandResult JointTrajectoryController::command(
    const JointTrajectoryCommand& command) {
  CommandResult result = updateTrajectoryCommand(command, 0, nullptr);
  if (result.ok()) preemptActiveGoal();
  return result;
}

JointTrajectoryController::CommandResult JointTrajectoryController::startGoal(
    GoalId goal, const JointTrajectoryCommand& command,
    const trajectory::GoalTolerances& tolerances) {
  CommandResult result;
  if (!running_) {
    result.error = "Can't accept new action goals. Controller is not running.";
    result.error_code = kInvalidGoal;
    return result;
  }
  const std::string mismatch = "Joints on incoming goal don't match the controller joints.";
  if (!options_.allow_partial_joints_goal && command.joint_names.size() != joint_names_.size()) {
    result.error = mismatch;
    result.error_code = kInvalidJoints;
    return result;
  }
  for (const std::string& name : command.joint_names) {  // internal::mapping
    if (std::find(joint_names_.begin(), joint_names_.end(), name) == joint_names_.end()) {
      result.error = mismatch;
      result.error_code = kInvalidJoints;
      return result;
    }
  }
  result = updateTrajectoryCommand(command, goal, &tolerances);
  if (!result.ok()) {
    result.error_code = kInvalidGoal;
    return result;
  }
  preemptActiveGoal();
  active_goal_ = goal;
  std::fill(done_.begin(), done_.end(), false);
  return result;
}

bool JointTrajectoryController::cancelGoal(GoalId goal) {
  if (goal == 0 || goal != active_goal_) return false;
  setHold(0);
  finishGoal(GoalEvent::Kind::kCanceled, 0, "");
  return true;
}

bool JointTrajectoryController::queryState(double time, State& state, std::string& error) const {
  if (!running_) {
    error = "Can't sample trajectory. Controller is not running.";
    return false;
  }
  return sampleTrajectory(trajectory_, uptime_ + (time - time_), state, error);
}

bool JointTrajectoryController::sampleTrajectory(const trajectory::Trajectory& trajectory,
                                                 double sample_time, State& state,
                                                 std::string& error) {
  state = State(trajectory.size());
  State joint_state;
  for (std::size_t i = 0; i < trajectory.size(); ++i) {
    if (trajectory::sampleSegments(trajectory[i], sample_time, joint_state) ==
        trajectory[i].end()) {
      error = "Requested sample time precedes trajectory start time.";
      return false;
    }
    state.position[i] = joint_state.position[0];
    state.velocity[i] = joint_state.velocity[0];
    state.acceleration[i] = joint_state.acceleration[0];
  }
  return true;
}

}  // namespace tianracer_control
