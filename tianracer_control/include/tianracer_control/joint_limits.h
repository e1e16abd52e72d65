// joint_limits_interface's saturation handles (ros_control noetic-devel,
// joint_limits_interface/include/joint_limits_interface/joint_limits_interface.h), the rules
// gazebo_ros_control's DefaultRobotHWSim registers for a joint without <safety_controller>
// and applies in writeSim (enforceLimits(period)) before the command reaches the joint.
// ROS-free maths only; the simulation's hardware (tianracer_sim/sim/robot_hw_sim.h) applies
// them as DefaultRobotHWSim does (issue 39, point 3).
#pragma once

#include <algorithm>
#include <cmath>
#include <limits>

namespace tianracer_control {

/// joint_limits_interface::JointLimits: which limits a joint has and their values.
struct JointLimits {
  bool has_position_limits = false;
  double min_position = 0.0;
  double max_position = 0.0;
  bool has_velocity_limits = false;
  double max_velocity = 0.0;
  bool has_acceleration_limits = false;
  double max_acceleration = 0.0;
  bool has_effort_limits = false;
  double max_effort = 0.0;
};

/// joint_limits_interface::SoftJointLimits (URDF <safety_controller>: soft_lower_limit,
/// soft_upper_limit, k_position, k_velocity).
struct SoftJointLimits {
  double min_position = 0.0;
  double max_position = 0.0;
  double k_position = 0.0;
  double k_velocity = 0.0;
};

namespace joint_limits_detail {
// internal::saturate: std::min(std::max(val, min_val), max_val)
inline double saturate(double v, double lo, double hi) { return std::min(std::max(v, lo), hi); }
}  // namespace joint_limits_detail

/// PositionJointSaturationHandle: the command within the position limits and, with a velocity
/// limit, within max_velocity * period of the previous (saturated) command; the first command
/// after a reset is measured from the joint's position.
class PositionSaturation {
 public:
  explicit PositionSaturation(const JointLimits& limits) : limits_(limits) {}
  double enforce(double command, double position, double period) {
    if (std::isnan(prev_cmd_)) prev_cmd_ = position;
    const double lo_limit =
        limits_.has_position_limits ? limits_.min_position : -std::numeric_limits<double>::max();
    const double hi_limit =
        limits_.has_position_limits ? limits_.max_position : std::numeric_limits<double>::max();
    double lo = lo_limit;
    double hi = hi_limit;
    if (limits_.has_velocity_limits) {
      const double delta = limits_.max_velocity * period;
      lo = std::max(prev_cmd_ - delta, lo_limit);
      hi = std::min(prev_cmd_ + delta, hi_limit);
    }
    prev_cmd_ = joint_limits_detail::saturate(command, lo, hi);
    return prev_cmd_;
  }
  void reset() { prev_cmd_ = std::numeric_limits<double>::quiet_NaN(); }

 private:
  JointLimits limits_;
  double prev_cmd_ = std::numeric_limits<double>::quiet_NaN();
};

/// VelocityJointSaturationHandle (upstream throws without a velocity limit): the command within
/// +-max_velocity and, with an acceleration limit, within max_acceleration * period of the
/// previous command (0 at first; upstream has no reset).
class VelocitySaturation {
 public:
  explicit VelocitySaturation(const JointLimits& limits) : limits_(limits) {}
  double enforce(double command, double period) {
    double lo = -limits_.max_velocity;
    double hi = limits_.max_velocity;
    if (limits_.has_acceleration_limits) {
      lo = std::max(prev_cmd_ - limits_.max_acceleration * period, -limits_.max_velocity);
      hi = std::min(prev_cmd_ + limits_.max_acceleration * period, limits_.max_velocity);
    }
    prev_cmd_ = joint_limits_detail::saturate(command, lo, hi);
    return prev_cmd_;
  }

 private:
  JointLimits limits_;
  double prev_cmd_ = 0.0;
};

/// EffortJointSaturationHandle (upstream throws without velocity and effort limits): the
/// command within +-max_effort; no effort further out past a position limit, nor further
/// faster past the velocity limit.
inline double enforceEffortSaturation(const JointLimits& limits, double command, double position,
                                      double velocity) {
  double lo = -limits.max_effort;
  double hi = limits.max_effort;
  if (limits.has_position_limits) {
    if (position < limits.min_position) {
      lo = 0.0;
    } else if (position > limits.max_position) {
      hi = 0.0;
    }
  }
  if (velocity < -limits.max_velocity) {
    lo = 0.0;
  } else if (velocity > limits.max_velocity) {
    hi = 0.0;
  }
  return joint_limits_detail::saturate(command, lo, hi);
}

/// PositionJointSoftLimitsHandle (upstream throws without a velocity limit): the velocity
/// bounds -k_position * (x - soft limit), within +-max_velocity, from the previous command x
/// (the joint's position after a reset), integrated over the period, within the hard limits.
class PositionSoftLimits {
 public:
  PositionSoftLimits(const JointLimits& limits, const SoftJointLimits& soft)
      : limits_(limits), soft_(soft) {}
  double enforce(double command, double position, double period) {
    using joint_limits_detail::saturate;
    if (std::isnan(prev_cmd_)) prev_cmd_ = position;
    const double pos = prev_cmd_;
    double soft_min_vel = -limits_.max_velocity;
    double soft_max_vel = limits_.max_velocity;
    if (limits_.has_position_limits) {
      soft_min_vel = saturate(-soft_.k_position * (pos - soft_.min_position),
                              -limits_.max_velocity, limits_.max_velocity);
      soft_max_vel = saturate(-soft_.k_position * (pos - soft_.max_position),
                              -limits_.max_velocity, limits_.max_velocity);
    }
    double pos_low = pos + soft_min_vel * period;
    double pos_high = pos + soft_max_vel * period;
    if (limits_.has_position_limits) {
      pos_low = std::max(pos_low, limits_.min_position);
      pos_high = std::min(pos_high, limits_.max_position);
    }
    prev_cmd_ = saturate(command, pos_low, pos_high);
    return prev_cmd_;
  }
  void reset() { prev_cmd_ = std::numeric_limits<double>::quiet_NaN(); }

 private:
  JointLimits limits_;
  SoftJointLimits soft_;
  double prev_cmd_ = std::numeric_limits<double>::quiet_NaN();
};

/// EffortJointSoftLimitsHandle (upstream throws without velocity and effort limits): the soft
/// velocity bounds as above from the joint's position, then the effort bounds
/// -k_velocity * (velocity - bound), within +-max_effort.
inline double enforceEffortSoftLimits(const JointLimits& limits, const SoftJointLimits& soft,
                                      double command, double position, double velocity) {
  using joint_limits_detail::saturate;
  double soft_min_vel = -limits.max_velocity;
  double soft_max_vel = limits.max_velocity;
  if (limits.has_position_limits) {
    soft_min_vel = saturate(-soft.k_position * (position - soft.min_position), -limits.max_velocity,
                            limits.max_velocity);
    soft_max_vel = saturate(-soft.k_position * (position - soft.max_position), -limits.max_velocity,
                            limits.max_velocity);
  }
  const double soft_min_eff =
      saturate(-soft.k_velocity * (velocity - soft_min_vel), -limits.max_effort, limits.max_effort);
  const double soft_max_eff =
      saturate(-soft.k_velocity * (velocity - soft_max_vel), -limits.max_effort, limits.max_effort);
  return saturate(command, soft_min_eff, soft_max_eff);
}

/// VelocityJointSoftLimitsHandle (no velocity limit: unbounded): the soft velocity bounds from
/// the joint's position and, with an acceleration limit, within max_acceleration * period of
/// the joint's velocity.
inline double enforceVelocitySoftLimits(const JointLimits& limits, const SoftJointLimits& soft,
                                        double command, double position, double velocity,
                                        double period) {
  using joint_limits_detail::saturate;
  const double max_vel =
      limits.has_velocity_limits ? limits.max_velocity : std::numeric_limits<double>::max();
  double min_v = -max_vel;
  double max_v = max_vel;
  if (limits.has_position_limits) {
    min_v = saturate(-soft.k_position * (position - soft.min_position), -max_vel, max_vel);
    max_v = saturate(-soft.k_position * (position - soft.max_position), -max_vel, max_vel);
  }
  if (limits.has_acceleration_limits) {
    min_v = std::max(velocity - limits.max_acceleration * period, min_v);
    max_v = std::min(velocity + limits.max_acceleration * period, max_v);
  }
  return saturate(command, min_v, max_v);
}

}  // namespace tianracer_control
