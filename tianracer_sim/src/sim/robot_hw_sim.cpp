#include "tianracer_sim/sim/robot_hw_sim.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <sstream>

#include <urdf_model/model.h>

#include <tianracer_control/pid_params.h>

#include "tianracer_sim/common/text.h"
#include "tianracer_sim/physics/world.h"

namespace tianracer_sim {

namespace tc = tianracer_control;

namespace {

/// Reads one joint's parameter dictionary as ros::NodeHandle::getParam does (an int is a
/// double; another kind is not there); a value of another kind or a non-finite number is
/// warned with its full name and treated as absent.
class JointParams {
 public:
  JointParams(const tc::ParamValue& tree, std::string where, const WarningSink& warn)
      : tree_(tree), where_(std::move(where)), warn_(warn) {}

  std::optional<bool> boolean(const std::string& key) const {
    const tc::ParamValue* v = tree_.find(key);
    if (!v) return std::nullopt;
    if (v->kind() == tc::ParamValue::Kind::kBool) return v->asBool();
    bad(key, std::string("is ") + v->typeName() + ", not a bool");
    return std::nullopt;
  }
  std::optional<double> number(const std::string& key) const {
    const tc::ParamValue* v = tree_.find(key);
    if (!v) return std::nullopt;
    if (const std::string why = tc::finiteNumberProblem(*v); !why.empty()) {
      bad(key, why);
      return std::nullopt;
    }
    return v->asNumber();
  }
  void warn(const std::string& message) const {
    if (warn_) warn_(where_ + ": " + message);
  }

 private:
  void bad(const std::string& key, const std::string& what) const {
    if (warn_) warn_(where_ + "/" + key + " " + what + "; ignored");
  }
  const tc::ParamValue& tree_;
  std::string where_;
  const WarningSink& warn_;
};

/// joint_limits_rosparam.h getJointLimits(name, nh): each has_* flag that is set decides;
/// true with its value(s) sets the limit, false clears it.
void applyJointLimitsParams(const JointParams& p, tc::JointLimits* l) {
  if (const auto has = p.boolean("has_position_limits")) {
    if (!*has) l->has_position_limits = false;
    const auto lo = p.number("min_position");
    const auto hi = p.number("max_position");
    if (*has && lo && hi) {
      l->has_position_limits = true;
      l->min_position = *lo;
      l->max_position = *hi;
    }
  }
  auto one = [&](const char* flag, const char* key, bool* has, double* value) {
    if (const auto set = p.boolean(flag)) {
      if (!*set) *has = false;
      const auto v = p.number(key);
      if (*set && v) {
        *has = true;
        *value = *v;
      }
    }
  };
  one("has_velocity_limits", "max_velocity", &l->has_velocity_limits, &l->max_velocity);
  one("has_acceleration_limits", "max_acceleration", &l->has_acceleration_limits,
      &l->max_acceleration);
  one("has_effort_limits", "max_effort", &l->has_effort_limits, &l->max_effort);
}

}  // namespace

tc::JointHandle makeJointHandle(const std::string& name, tc::JointHandle::Interface iface,
                                const JointInfo* joint) {
  tc::JointHandle h;
  h.name = name;
  h.interface = iface;
  if (joint) {
    h.has_position_limits = joint->has_position_limits;
    h.lower = joint->lower;
    h.upper = joint->upper;
    h.velocity_limit = joint->velocity_limit;
    h.effort_limit = joint->effort_limit;
    h.continuous = joint->type == JointType::kContinuous;
  }
  return h;
}

void RobotHwSim::init(const RobotModel& model, const std::vector<tc::JointHandle>& handles,
                      const RobotHwSimParams& params, const WarningSink& warn) {
  joints_.clear();
  joints_.resize(handles.size());
  held_.assign(handles.size(), 0.0);
  e_stop_ = last_e_stop_ = was_stopped_ = false;
  for (size_t k = 0; k < handles.size(); ++k) {
    const tc::JointHandle& h = handles[k];
    Joint& j = joints_[k];
    switch (h.interface) {
      case tc::JointHandle::Interface::kEffort: j.method = Method::kEffort; break;
      case tc::JointHandle::Interface::kPosition: j.method = Method::kPosition; break;
      case tc::JointHandle::Interface::kVelocity: j.method = Method::kVelocity; break;
    }

    // registerJointLimits: the URDF (joint_limits_urdf.h), then the parameters.
    bool has_limits = false, has_soft = false;
    urdf::JointConstSharedPtr uj = model.urdf ? model.urdf->getJoint(h.name) : nullptr;
    if (uj) {
      if (uj->type == urdf::Joint::REVOLUTE) j.type = Joint::Type::kRevolute;
      if (uj->type == urdf::Joint::CONTINUOUS) j.type = Joint::Type::kContinuous;
      if (uj->limits) {
        has_limits = true;
        j.limits.has_position_limits =
            uj->type == urdf::Joint::REVOLUTE || uj->type == urdf::Joint::PRISMATIC;
        if (j.limits.has_position_limits) {
          j.limits.min_position = uj->limits->lower;
          j.limits.max_position = uj->limits->upper;
        }
        j.limits.has_velocity_limits = true;
        j.limits.max_velocity = uj->limits->velocity;
        j.limits.has_acceleration_limits = false;
        j.limits.has_effort_limits = true;
        j.limits.max_effort = uj->limits->effort;
      }
      if (uj->safety) {
        has_soft = true;
        j.soft.min_position = uj->safety->soft_lower_limit;
        j.soft.max_position = uj->safety->soft_upper_limit;
        j.soft.k_position = uj->safety->k_position;
        j.soft.k_velocity = uj->safety->k_velocity;
      }
    }
    const std::string limits_name = params.ns + "/joint_limits/" + h.name;
    if (const tc::ParamValue* t = params.joint_limits.find(h.name)) {
      const JointParams p(*t, limits_name, warn);
      if (t->kind() != tc::ParamValue::Kind::kDict) {
        p.warn(std::string("is ") + t->typeName() + ", not a dictionary; ignored");
      } else {
        has_limits = true;
        applyJointLimitsParams(p, &j.limits);
      }
    }

    if (has_limits) {
      // The handles' constructors throw (and Gazebo stops) without the limits they need;
      // here the joint goes unlimited with upstream's words.
      const bool vel = j.limits.has_velocity_limits, eff = j.limits.has_effort_limits;
      std::string missing;
      if (has_soft) {
        if (j.method == Method::kEffort || j.method == Method::kPosition)
          missing = !vel ? "velocity" : (j.method == Method::kEffort && !eff ? "effort" : "");
      } else {
        if (j.method == Method::kEffort || j.method == Method::kVelocity)
          missing = !vel ? "velocity" : (j.method == Method::kEffort && !eff ? "effort" : "");
      }
      if (!missing.empty()) {
        if (warn) {
          warn(limits_name + ": cannot enforce limits for joint '" + h.name + "'. It has no " +
               missing + " limits specification (joint_limits_interface); its command is not "
               "limited");
        }
      } else {
        j.limits_kind = has_soft ? Limits::kSoftLimits : Limits::kSaturation;
        if (j.method == Method::kPosition && has_soft) j.position_soft.emplace(j.limits, j.soft);
        if (j.method == Method::kPosition && !has_soft) j.position_saturation.emplace(j.limits);
        if (j.method == Method::kVelocity && !has_soft) j.velocity_saturation.emplace(j.limits);
      }
    }

    // pid_gains/<joint> for position and velocity joints (control_toolbox::Pid::init).
    if (j.method == Method::kEffort) continue;
    const tc::ParamValue* g = params.pid_gains.find(h.name);
    if (!g) continue;
    const std::string pid_name = params.ns + "/gazebo_ros_control/pid_gains/" + h.name;
    const JointParams p(*g, pid_name, warn);
    if (g->kind() != tc::ParamValue::Kind::kDict) {
      p.warn(std::string("is ") + g->typeName() + ", not a dictionary; ignored");
      continue;
    }
    const tc::PidParams pp = tc::readPidParams(p);
    if (!pp.p) {
      // control_toolbox: "No p gain specified for pid." and init() fails: no PID.
      p.warn("no p gain specified for pid; joint '" + h.name + "' is driven without one");
      continue;
    }
    try {
      j.pid = tc::Pid(tc::toPidGains(h.name, pp, WarningSink()));
    } catch (const tc::ControllerError& e) {
      p.warn(std::string(e.what()) + "; joint '" + h.name + "' is driven without a PID");
      continue;
    }
    j.method = j.method == Method::kPosition ? Method::kPositionPid : Method::kVelocityPid;
  }
}

bool RobotHwSim::takeEStopReleased() {
  // GRCP Update: reset_ctrlrs on the first update after the stop.
  if (e_stop_) {
    was_stopped_ = true;
    return false;
  }
  const bool released = was_stopped_;
  was_stopped_ = false;
  return released;
}

void RobotHwSim::beginWrite(const std::vector<tc::JointHandle>& handles) {
  if (e_stop_) {
    if (!last_e_stop_) {
      for (size_t k = 0; k < handles.size() && k < held_.size(); ++k) held_[k] = handles[k].position;
      last_e_stop_ = true;
    }
  } else {
    last_e_stop_ = false;
  }
}

JointDrive RobotHwSim::write(size_t k, tc::JointHandle& h, double period) {
  Joint& j = joints_.at(k);
  const bool position_command = j.method == Method::kPosition || j.method == Method::kPositionPid;
  if (e_stop_ && position_command) h.command = held_[k];

  // enforceLimits(period) of the registered handle.
  if (j.limits_kind == Limits::kSaturation) {
    if (j.position_saturation) h.command = j.position_saturation->enforce(h.command, h.position, period);
    if (j.velocity_saturation) h.command = j.velocity_saturation->enforce(h.command, period);
    if (j.method == Method::kEffort)
      h.command = tc::enforceEffortSaturation(j.limits, h.command, h.position, h.velocity);
  } else if (j.limits_kind == Limits::kSoftLimits) {
    if (j.position_soft) h.command = j.position_soft->enforce(h.command, h.position, period);
    if (j.method == Method::kVelocity || j.method == Method::kVelocityPid)
      h.command = tc::enforceVelocitySoftLimits(j.limits, j.soft, h.command, h.position,
                                                h.velocity, period);
    if (j.method == Method::kEffort)
      h.command = tc::enforceEffortSoftLimits(j.limits, j.soft, h.command, h.position, h.velocity);
  }

  JointDrive d;
  const double cap = j.effortLimit();  // DRS SetParam("fmax", effort limit): DBL_MAX without one
  switch (j.method) {
    case Method::kEffort:
      d.mode = JointDrive::Mode::kEffort;
      d.value = e_stop_ ? 0.0 : h.command;
      break;
    case Method::kPosition:
      d.mode = JointDrive::Mode::kPosition;
      d.value = h.command;
      d.max_effort = cap;
      break;
    case Method::kVelocity:
      d.mode = JointDrive::Mode::kVelocity;
      d.value = e_stop_ ? 0.0 : h.command;
      d.max_effort = cap;
      break;
    case Method::kPositionPid:
    case Method::kVelocityPid: {
      const double error = j.method == Method::kPositionPid
                               ? positionPidError(j, h.position, h.command)
                               : (e_stop_ ? -h.velocity : h.command - h.velocity);
      d.mode = JointDrive::Mode::kEffort;
      d.value = std::clamp(j.pid.computeCommand(error, period), -j.effortLimit(), j.effortLimit());
      break;
    }
  }
  return d;
}

void RobotHwSim::reset() {
  for (Joint& j : joints_) {
    if (j.position_saturation) j.position_saturation->reset();
    if (j.position_soft) j.position_soft->reset();
    if (j.velocity_saturation) j.velocity_saturation.emplace(j.limits);
    j.pid.reset();
  }
}

double positionPidError(const RobotHwSim::Joint& joint, double position, double command) {
  auto shortest = [](double from, double to) {
    double d = std::fmod(to - from + M_PI, 2.0 * M_PI);
    if (d < 0.0) d += 2.0 * M_PI;
    return d - M_PI;
  };
  if (joint.type == RobotHwSim::Joint::Type::kContinuous) return shortest(position, command);
  if (joint.type == RobotHwSim::Joint::Type::kRevolute) {
    const tc::JointLimits& l = joint.limits;
    if (l.has_position_limits && l.max_position - l.min_position < 2.0 * M_PI)
      return command - position;
    return shortest(position, command);
  }
  return command - position;
}

}  // namespace tianracer_sim
