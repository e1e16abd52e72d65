#include "tianracer_control/joint_controllers.h"

#include <algorithm>
#include <cmath>
#include <set>
#include <sstream>

namespace tianracer_control {

namespace {

constexpr char kJointState[] = "joint_state_controller/JointStateController";
constexpr char kEffortPosition[] = "effort_controllers/JointPositionController";
constexpr char kEffortVelocity[] = "effort_controllers/JointVelocityController";
constexpr char kEffortEffort[] = "effort_controllers/JointEffortController";
constexpr char kVelocityVelocity[] = "velocity_controllers/JointVelocityController";
constexpr char kPositionPosition[] = "position_controllers/JointPositionController";

std::string prefix(const std::string& controller) { return "controller '" + controller + "': "; }

double clampSymmetric(double x, double limit) {
  return limit > 0.0 ? std::min(std::max(x, -limit), limit) : x;
}

double clampToPositionLimits(const JointHandle& j, double x) {
  return j.has_position_limits ? std::min(std::max(x, j.lower), j.upper) : x;
}

// "the effort interface (EffortJointInterface)"
std::string describe(JointHandle::Interface iface) {
  const char* word = iface == JointHandle::Interface::kEffort     ? "effort"
                     : iface == JointHandle::Interface::kVelocity ? "velocity"
                                                                  : "position";
  return std::string("the ") + word + " interface (" + toString(iface) + ")";
}

}  // namespace

const char* toString(JointHandle::Interface iface) {
  switch (iface) {
    case JointHandle::Interface::kEffort:
      return "EffortJointInterface";
    case JointHandle::Interface::kVelocity:
      return "VelocityJointInterface";
    case JointHandle::Interface::kPosition:
      return "PositionJointInterface";
  }
  return "?";
}

double shortestAngularDistance(double from, double to) {
  const double two_pi = 2.0 * M_PI;
  double d = std::fmod(to - from + M_PI, two_pi);
  if (d < 0.0) d += two_pi;
  return d - M_PI;
}

// ---------------------------------------------------------------------------------------------
PidGains toPidGains(const std::string& controller, const PidParams& params,
                    const WarningSink& warn) {
  const std::string pre = prefix(controller);
  if (!params.p) throw ControllerError(pre + "pid/p is missing (pid gains are required)");
  auto finite = [&](const std::optional<double>& v, const char* key) {
    if (v && !std::isfinite(*v)) {
      std::ostringstream os;
      os << pre << "pid/" << key << " must be finite, got " << *v;
      throw ControllerError(os.str());
    }
  };
  finite(params.p, "p");
  finite(params.i, "i");
  finite(params.d, "d");
  finite(params.i_clamp, "i_clamp");
  finite(params.i_clamp_min, "i_clamp_min");
  finite(params.i_clamp_max, "i_clamp_max");

  const double i_clamp = std::abs(params.i_clamp.value_or(0.0));
  PidGains g = PidGains::fromIClamp(*params.p, params.i.value_or(0.0), params.d.value_or(0.0),
                                    i_clamp, params.antiwindup.value_or(false));
  if (params.i_clamp_min) g.i_clamp_min = *params.i_clamp_min;
  if (params.i_clamp_max) g.i_clamp_max = *params.i_clamp_max;
  if (g.i_clamp_min > g.i_clamp_max) {
    std::ostringstream os;
    os << pre << "pid/i_clamp_min (" << g.i_clamp_min << ") is greater than pid/i_clamp_max ("
       << g.i_clamp_max << ")";
    throw ControllerError(os.str());
  }
  if (warn && g.i != 0.0 && g.i_clamp_min == 0.0 && g.i_clamp_max == 0.0) {
    warn(pre + "pid/i is " + std::to_string(g.i) +
         " but the integral clamp is 0, so the integral term is always 0 (set pid/i_clamp)");
  }
  return g;
}

// ---------------------------------------------------------------------------------------------
JointStateController::JointStateController(std::string name, double publish_rate)
    : Controller(std::move(name), kJointState), rate_(publish_rate), period_(1.0 / publish_rate) {}

void JointStateController::starting(double time) {
  next_ = time;
  started_ = true;
}

bool JointStateController::due(double t) {
  // Tolerance for accumulated floating point error of a fixed-step clock.
  const double eps = 1e-9 * std::max(1.0, std::abs(t));
  if (!started_ || t < next_ - period_ - eps) {  // first call, or time went backwards
    next_ = t;
    started_ = true;
  }
  if (t + eps < next_) return false;
  next_ += period_;
  if (next_ + eps <= t) next_ = t + period_;  // after a long gap: no burst
  return true;
}

// ---------------------------------------------------------------------------------------------
EffortJointPositionController::EffortJointPositionController(std::string name, JointHandle* joint,
                                                             const PidGains& gains)
    : SingleJointController(std::move(name), kEffortPosition, joint), pid_(gains) {}

void EffortJointPositionController::starting(double) {
  command_ = clampToPositionLimits(*joint_, joint_->position);
  pid_.reset();
}

bool EffortJointPositionController::setCommand(double value) {
  if (!std::isfinite(value)) return false;
  command_ = clampToPositionLimits(*joint_, value);
  return true;
}

void EffortJointPositionController::update(double dt) {
  const double error = joint_->continuous ? shortestAngularDistance(joint_->position, command_)
                                          : command_ - joint_->position;
  const double error_dot = 0.0 - joint_->velocity;
  joint_->command = clampSymmetric(pid_.computeCommand(error, error_dot, dt), joint_->effort_limit);
}

// ---------------------------------------------------------------------------------------------
EffortJointVelocityController::EffortJointVelocityController(std::string name, JointHandle* joint,
                                                             const PidGains& gains)
    : SingleJointController(std::move(name), kEffortVelocity, joint), pid_(gains) {}

void EffortJointVelocityController::starting(double) {
  command_ = 0.0;
  pid_.reset();
}

bool EffortJointVelocityController::setCommand(double value) {
  if (!std::isfinite(value)) return false;
  command_ = clampSymmetric(value, joint_->velocity_limit);
  return true;
}

void EffortJointVelocityController::update(double dt) {
  const double error = command_ - joint_->velocity;
  joint_->command = clampSymmetric(pid_.computeCommand(error, dt), joint_->effort_limit);
}

// ---------------------------------------------------------------------------------------------
void EffortForwardController::starting(double) { command_ = 0.0; }

bool EffortForwardController::setCommand(double value) {
  if (!std::isfinite(value)) return false;
  command_ = clampSymmetric(value, joint_->effort_limit);
  return true;
}

void EffortForwardController::update(double) { joint_->command = command_; }

void VelocityForwardController::starting(double) { command_ = 0.0; }

bool VelocityForwardController::setCommand(double value) {
  if (!std::isfinite(value)) return false;
  command_ = clampSymmetric(value, joint_->velocity_limit);
  return true;
}

void VelocityForwardController::update(double) { joint_->command = command_; }

void PositionForwardController::starting(double) {
  command_ = clampToPositionLimits(*joint_, joint_->position);
}

bool PositionForwardController::setCommand(double value) {
  if (!std::isfinite(value)) return false;
  command_ = clampToPositionLimits(*joint_, value);
  return true;
}

void PositionForwardController::update(double) { joint_->command = command_; }

// ---------------------------------------------------------------------------------------------
const std::vector<std::string>& knownControllerTypes() {
  static const std::vector<std::string> types = {kJointState,    kEffortPosition,
                                                 kEffortVelocity, kEffortEffort,
                                                 kVelocityVelocity, kPositionPosition};
  return types;
}

namespace {

void warnUnknownKeys(const ControllerSpec& spec, bool uses_joint, bool uses_pid,
                     bool uses_rate, const WarningSink& warn) {
  if (!warn) return;
  std::set<std::string> allowed = {"type"};
  if (uses_joint) allowed.insert("joint");
  if (uses_rate) allowed.insert("publish_rate");
  if (uses_pid) {
    for (const char* k : {"pid", "pid/p", "pid/i", "pid/d", "pid/i_clamp", "pid/i_clamp_min",
                          "pid/i_clamp_max", "pid/antiwindup"}) {
      allowed.insert(k);
    }
  }
  for (const std::string& key : spec.keys) {
    if (allowed.count(key) == 0) {
      warn(formatLocation("", spec.line) + prefix(spec.name) + "key '" + key +
           "' is not used by " + spec.type + ", ignored");
    }
  }
}

}  // namespace

std::unique_ptr<Controller> makeController(const ControllerSpec& spec,
                                           std::map<std::string, JointHandle*>& joints,
                                           const WarningSink& warn) {
  const std::string pre = formatLocation("", spec.line) + prefix(spec.name);
  if (spec.name.empty()) throw ControllerError(pre + "the controller name is empty");
  if (spec.type.empty()) throw ControllerError(pre + "no type given (parameter 'type')");

  using Iface = JointHandle::Interface;
  struct TypeInfo {
    Iface iface;
    bool pid;
  };
  static const std::map<std::string, TypeInfo> single_joint = {
      {kEffortPosition, {Iface::kEffort, true}},
      {kEffortVelocity, {Iface::kEffort, true}},
      {kEffortEffort, {Iface::kEffort, false}},
      {kVelocityVelocity, {Iface::kVelocity, false}},
      {kPositionPosition, {Iface::kPosition, false}},
  };

  if (spec.type == kJointState) {
    warnUnknownKeys(spec, false, false, true, warn);
    if (!spec.publish_rate) {
      throw ControllerError(pre + "publish_rate is missing (" + spec.type + ")");
    }
    if (!(*spec.publish_rate > 0.0) || !std::isfinite(*spec.publish_rate)) {
      std::ostringstream os;
      os << pre << "publish_rate must be a positive number, got " << *spec.publish_rate;
      throw ControllerError(os.str());
    }
    return std::make_unique<JointStateController>(spec.name, *spec.publish_rate);
  }

  const auto type_it = single_joint.find(spec.type);
  if (type_it == single_joint.end()) {
    std::string known;
    for (const std::string& t : knownControllerTypes()) known += (known.empty() ? "" : ", ") + t;
    throw ControllerError(pre + "unknown type '" + spec.type + "' (known types: " +
                          known + ")");
  }
  const TypeInfo& info = type_it->second;
  warnUnknownKeys(spec, true, info.pid, false, warn);

  if (spec.joint.empty()) {
    throw ControllerError(pre + "no joint given (parameter 'joint' of " + spec.type + ")");
  }
  const auto joint_it = joints.find(spec.joint);
  if (joint_it == joints.end() || joint_it->second == nullptr) {
    std::string names;
    for (const auto& kv : joints) names += (names.empty() ? "" : ", ") + kv.first;
    throw ControllerError(pre + "joint '" + spec.joint + "' not found among the joints with a " +
                          "transmission (" + (names.empty() ? "none" : names) + ")");
  }
  JointHandle* joint = joint_it->second;
  if (joint->interface != info.iface) {
    throw ControllerError(pre + spec.type + " needs " + describe(info.iface) +
                          " but the transmission of joint '" + spec.joint + "' gives " +
                          describe(joint->interface));
  }

  if (spec.type == kEffortPosition || spec.type == kEffortVelocity) {
    if (!spec.pid || !spec.pid->p) {
      throw ControllerError(pre + "pid/p is missing (" + spec.type + " needs pid gains)");
    }
    const PidGains gains = toPidGains(spec.name, *spec.pid, warn);
    if (spec.type == kEffortPosition) {
      return std::make_unique<EffortJointPositionController>(spec.name, joint, gains);
    }
    return std::make_unique<EffortJointVelocityController>(spec.name, joint, gains);
  }
  if (spec.type == kEffortEffort) {
    return std::make_unique<EffortForwardController>(spec.name, kEffortEffort, joint);
  }
  if (spec.type == kVelocityVelocity) {
    return std::make_unique<VelocityForwardController>(spec.name, kVelocityVelocity, joint);
  }
  return std::make_unique<PositionForwardController>(spec.name, kPositionPosition, joint);
}

// ---------------------------------------------------------------------------------------------
Controller& ControllerSet::add(std::unique_ptr<Controller> controller, double time) {
  if (!controller) throw ControllerError("ControllerSet::add: null controller");
  for (const auto& c : controllers_) {
    if (c->name() == controller->name()) {
      throw ControllerError(prefix(controller->name()) + "a controller of that name is loaded");
    }
    if (controller->joint() != nullptr && c->joint() == controller->joint()) {
      throw ControllerError(prefix(controller->name()) + "joint '" + controller->joint()->name +
                            "' is already commanded by controller '" + c->name() + "'");
    }
  }
  controller->starting(time);
  controllers_.push_back(std::move(controller));
  return *controllers_.back();
}

Controller& ControllerSet::load(const ControllerSpec& spec,
                                std::map<std::string, JointHandle*>& joints, double time,
                                const WarningSink& warn) {
  return add(makeController(spec, joints, warn), time);
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
