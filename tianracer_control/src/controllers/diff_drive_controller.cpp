#include "tianracer_control/controllers/diff_drive_controller.h"

#include <cmath>
#include <limits>
#include <sstream>

#include <urdf_model/model.h>

namespace tianracer_control {

std::vector<std::string> readWheelNames(ControllerParams& params, const std::string& key) {
  const std::string pre = params.prefix();
  const ParamValue* v = params.value(key);
  if (!v) throw ControllerError(pre + "Couldn't retrieve wheel param '" + key + "'.");
  if (v->kind() == ParamValue::Kind::kString) return {v->asString()};
  if (v->kind() != ParamValue::Kind::kList) {
    throw ControllerError(pre + "Wheel param '" + key +
                          "' is neither a list of strings nor a string.");
  }
  if (v->items().empty()) {
    throw ControllerError(pre + "Wheel param '" + key + "' is an empty list");
  }
  std::vector<std::string> names;
  for (std::size_t i = 0; i < v->items().size(); ++i) {
    if (v->items()[i].kind() != ParamValue::Kind::kString) {
      throw ControllerError(pre + "Wheel param '" + key + "' #" + std::to_string(i) +
                            " isn't a string.");
    }
    names.push_back(v->items()[i].asString());
  }
  return names;
}

std::unique_ptr<Controller> DiffDriveController::create(ControllerContext& context) {
  ControllerParams& params = context.params;
  const std::string pre = params.prefix();
  Params p;
  p.left_wheels = readWheelNames(params, "left_wheel");
  p.right_wheels = readWheelNames(params, "right_wheel");
  if (p.left_wheels.size() != p.right_wheels.size()) {
    throw ControllerError(pre + "#left wheels (" + std::to_string(p.left_wheels.size()) +
                          ") != #right wheels (" + std::to_string(p.right_wheels.size()) + ").");
  }
  Common common = readCommon(params);
  common.publish_cmd = params.boolean("publish_cmd").value_or(false);
  p.wheel_separation_multiplier =
      params.positiveNumber("wheel_separation_multiplier", p.wheel_separation_multiplier);
  if (params.value("wheel_radius_multiplier")) {
    p.left_wheel_radius_multiplier = p.right_wheel_radius_multiplier =
        params.positiveNumber("wheel_radius_multiplier", 1.0);
  } else {
    p.left_wheel_radius_multiplier = params.positiveNumber("left_wheel_radius_multiplier", 1.0);
    p.right_wheel_radius_multiplier = params.positiveNumber("right_wheel_radius_multiplier", 1.0);
  }
  p.publish_wheel_joint_controller_state =
      params.boolean("publish_wheel_joint_controller_state").value_or(false);

  // setOdomParamsFromUrdf(): what is not given comes from the first wheel of each side.
  const std::optional<double> separation = params.number("wheel_separation");
  const std::optional<double> radius = params.number("wheel_radius");
  if (!separation || !radius) {
    const urdf::ModelInterface* urdf = context.robot_description;
    if (!urdf) {
      throw ControllerError(pre + "Robot description couldn't be retrieved from param server.");
    }
    const urdf::JointConstSharedPtr left = urdf->getJoint(p.left_wheels[0]);
    const urdf::JointConstSharedPtr right = urdf->getJoint(p.right_wheels[0]);
    for (const auto& [joint, name] : {std::pair(left, p.left_wheels[0]),
                                      std::pair(right, p.right_wheels[0])}) {
      if (!joint) {
        throw ControllerError(pre + name + " couldn't be retrieved from model description");
      }
    }
    if (!separation) {
      // The distance between the two joints' origins, each in its parent link's frame.
      const urdf::Vector3& a = left->parent_to_joint_origin_transform.position;
      const urdf::Vector3& b = right->parent_to_joint_origin_transform.position;
      p.wheel_separation = std::sqrt((a.x - b.x) * (a.x - b.x) + (a.y - b.y) * (a.y - b.y) +
                                     (a.z - b.z) * (a.z - b.z));
    }
    if (!radius) p.wheel_radius = wheelRadiusFromUrdf(*urdf, p.left_wheels[0], pre);
  }
  if (separation) p.wheel_separation = *separation;
  if (radius) p.wheel_radius = *radius;
  if (!(p.wheel_separation > 0.0) || !std::isfinite(p.wheel_separation)) {
    throw ControllerError(pre + "wheel_separation must be positive, got " +
                          numberText(p.wheel_separation) +
                          (separation ? "" : " (from the wheel joints' origins in the URDF)"));
  }
  if (!(p.wheel_radius > 0.0) || !std::isfinite(p.wheel_radius)) {
    throw ControllerError(pre + "wheel_radius must be positive, got " + numberText(p.wheel_radius));
  }

  std::vector<JointHandle*> left, right;
  for (std::size_t i = 0; i < p.left_wheels.size(); ++i) {
    left.push_back(findJoint(context, p.left_wheels[i], JointHandle::Interface::kVelocity));
    right.push_back(findJoint(context, p.right_wheels[i], JointHandle::Interface::kVelocity));
  }
  return std::make_unique<DiffDriveController>(params.name(), std::move(common), std::move(p),
                                               std::move(left), std::move(right));
}

DiffDriveController::DiffDriveController(std::string name, Common common, Params params,
                                         std::vector<JointHandle*> left,
                                         std::vector<JointHandle*> right)
    : CmdVelDriveController(std::move(name), kType, std::move(common)),
      params_(std::move(params)),
      left_(std::move(left)),
      right_(std::move(right)) {
  odometry_.setWheelParams(wheelSeparation(), leftWheelRadius(), rightWheelRadius());
}

std::vector<const JointHandle*> DiffDriveController::claimedJoints() const {
  std::vector<const JointHandle*> out(left_.begin(), left_.end());
  out.insert(out.end(), right_.begin(), right_.end());
  return out;
}

void DiffDriveController::setWheels(double left, double right) {
  for (JointHandle* j : left_) j->command = left;
  for (JointHandle* j : right_) j->command = right;
}

void DiffDriveController::brake() { setWheels(0.0, 0.0); }

void DiffDriveController::resetOdometry() {
  double left = 0.0, right = 0.0;
  for (std::size_t i = 0; i < left_.size(); ++i) {
    left += left_[i]->position / left_.size();
    right += right_[i]->position / right_.size();
  }
  odometry_.setWheelParams(wheelSeparation(), leftWheelRadius(), rightWheelRadius());
  odometry_.resetPose(left, right);
}

void DiffDriveController::setDynamicParams(const DynamicParams& d) {
  params_.left_wheel_radius_multiplier = d.left_wheel_radius_multiplier;
  params_.right_wheel_radius_multiplier = d.right_wheel_radius_multiplier;
  params_.wheel_separation_multiplier = d.wheel_separation_multiplier;
  common_.publish_rate = d.publish_rate;
  common_.enable_odom_tf = d.enable_odom_tf;
}

DiffDriveController::DynamicParams DiffDriveController::dynamicParams() const {
  return {params_.left_wheel_radius_multiplier, params_.right_wheel_radius_multiplier,
          params_.wheel_separation_multiplier, common_.publish_rate, common_.enable_odom_tf};
}

bool DiffDriveController::updateOdometry(double time) {
  odometry_.setWheelParams(wheelSeparation(), leftWheelRadius(), rightWheelRadius());
  double left = 0.0, right = 0.0;
  for (std::size_t i = 0; i < left_.size(); ++i) {
    const double lp = left_[i]->position, rp = right_[i]->position;
    if (std::isnan(lp) || std::isnan(rp)) return false;
    left += lp;
    right += rp;
  }
  odometry_.update(left / left_.size(), right / right_.size(), time);
  return true;
}

void DiffDriveController::drive(double lin, double ang) {
  const double ws = wheelSeparation();
  setWheels((lin - ang * ws / 2.0) / leftWheelRadius(), (lin + ang * ws / 2.0) / rightWheelRadius());
  publishWheelData(lin, ang);
  time_previous_ = now();
}

void DiffDriveController::starting(double time) {
  CmdVelDriveController::starting(time);
  time_previous_ = time;
}

std::vector<std::string> DiffDriveController::wheelJointNames() const {
  std::vector<std::string> names;
  for (const JointHandle* j : left_) names.push_back(j->name);
  for (const JointHandle* j : right_) names.push_back(j->name);
  return names;
}

std::vector<DiffDriveController::WheelState> DiffDriveController::takeWheelStates() {
  return wheel_states_.take();
}

// Upstream's publishWheelData (diff_drive_controller.cpp), term for term.
void DiffDriveController::publishWheelData(double lin, double ang) {
  if (!params_.publish_wheel_joint_controller_state) return;
  const std::size_t n = left_.size(), all = 2 * n;
  if (desired_positions_.size() != all) {
    desired_positions_.assign(all, 0.0);
    vel_previous_.assign(all, 0.0);
  }
  const double time = now(), cmd_dt = update_dt_;
  const double ws = wheelSeparation();
  const double vel_left_desired = (lin - ang * ws / 2.0) / leftWheelRadius();
  const double vel_right_desired = (lin + ang * ws / 2.0) / rightWheelRadius();
  const double control_duration = time - time_previous_;
  WheelState s;
  s.t = time;
  for (WheelState::Point* p : {&s.desired, &s.actual, &s.error}) {
    p->positions.resize(all);
    p->velocities.resize(all);
    p->accelerations.resize(all);
    p->effort.resize(all);
  }
  // Wheel pair by pair, left k = i then right k = i + n, as upstream; it saves the desired
  // velocities as "previous" inside that loop, so with several wheels a side every pair after
  // the first reports a desired acceleration of 0.
  for (std::size_t i = 0; i < n; ++i) {
    for (const std::size_t k : {i, i + n}) {
      const JointHandle& j = k < n ? *left_[k] : *right_[k - n];
      const double v_desired = k < n ? vel_left_desired : vel_right_desired;
      const double v_desired_previous = k < n ? vel_left_desired_previous_ : vel_right_desired_previous_;
      s.actual.positions[k] = j.position;
      s.actual.velocities[k] = j.velocity;
      s.actual.accelerations[k] = (j.velocity - vel_previous_[k]) / control_duration;
      s.actual.effort[k] = j.effort;
      desired_positions_[k] += v_desired * cmd_dt;
      s.desired.positions[k] = desired_positions_[k];
      s.desired.velocities[k] = v_desired;
      s.desired.accelerations[k] = (v_desired - v_desired_previous) * cmd_dt;
      s.desired.effort[k] = std::numeric_limits<double>::quiet_NaN();
      s.error.positions[k] = s.desired.positions[k] - s.actual.positions[k];
      s.error.velocities[k] = s.desired.velocities[k] - s.actual.velocities[k];
      s.error.accelerations[k] = s.desired.accelerations[k] - s.actual.accelerations[k];
      s.error.effort[k] = s.desired.effort[k] - s.actual.effort[k];
      vel_previous_[k] = j.velocity;
    }
    vel_left_desired_previous_ = vel_left_desired;
    vel_right_desired_previous_ = vel_right_desired;
  }
  wheel_states_.post(std::move(s));
}

}  // namespace tianracer_control
