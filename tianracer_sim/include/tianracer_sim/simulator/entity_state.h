// Poses and twists of models and links relative to other entities, Gazebo's entity names
// ("model", "model::link"), and external wrenches on a schedule: the ROS-free part of the
// Gazebo interface (ros/gazebo_interface.h). Frames: X_AB is the pose of B in A; twists are
// the velocity of a frame's origin and its angular velocity, both in the world frame W.
#ifndef TIANRACER_SIM_SIMULATOR_ENTITY_STATE_H
#define TIANRACER_SIM_SIMULATOR_ENTITY_STATE_H

#include <string>
#include <vector>

#include <Eigen/Geometry>

#include "tianracer_sim/physics/world.h"

namespace tianracer_sim {

/// Pose and twist of an entity (a model's canonical link or a link) in the world frame.
struct EntityState {
  Eigen::Isometry3d X_WE = Eigen::Isometry3d::Identity();
  Twist V_WE;
};

/// "model::link" -> {"model", "link"}; "model" -> {"model", ""}. Only the first "::" splits
/// (a link name may itself contain "::" in nested SDF models).
struct ScopedName {
  std::string model, link;
};
ScopedName splitScopedName(const std::string& name);

/// "", "world" and "map" name the world frame (gazebo_ros's convention).
bool isWorldFrame(const std::string& name);

/// What get_model_state / get_link_state report for entity E relative to frame F, as
/// gazebo_ros does: the pose X_FE = X_WF^-1 X_WE; the velocities as differences in the world
/// frame rotated into F, v = R_WF^T (v_WE - v_WF), w = R_WF^T (w_WE - w_WF) (no transport
/// term: F's rotation does not add w_F x r).
EntityState relativeTo(const EntityState& entity, const EntityState& frame);

/// What set_model_state / set_link_state mean by a state given in frame F: X_WE = X_WF X_FE;
/// the twist is rotated into the world, v_W = R_WF v_F, w_W = R_WF w_F (gazebo_ros does not add
/// F's own velocity either).
EntityState fromFrame(const EntityState& in_frame, const EntityState& frame);

/// The twist of a rigid body's frame B when a frame L fixed to it has twist V_WL:
/// w_B = w_L, v_B = v_L + w_L x (p_B - p_L).
Twist shiftTwist(const Twist& V_WL, const Eigen::Vector3d& p_WL, const Eigen::Vector3d& p_WB);

/// An external wrench on a body (apply_body_wrench), in the world frame: the force through
/// the body's centre of mass and a torque, applied over [start, end) of sim time
/// (end = +inf: until cleared).
struct ScheduledWrench {
  std::string body;  // "model::link"
  Eigen::Vector3d force_W = Eigen::Vector3d::Zero();
  Eigen::Vector3d torque_W = Eigen::Vector3d::Zero();
  double start = 0.0, end = 0.0;
};

/// The wrenches asked for, summed per body at each step.
class WrenchSchedule {
 public:
  /// gazebo_ros's rules: a start in the past (or 0) means now; duration < 0 means until
  /// cleared, 0 means nothing (returns false), and shorter than one step means one step.
  bool add(ScheduledWrench wrench, double now, double duration, double dt);
  /// Removes every wrench on `body` ("" = all); returns how many.
  int clear(const std::string& body = "");
  /// Sum of the wrenches active at time t on each body that has any, sorted by body name;
  /// drops the ones that have ended. A body whose wrenches all ended is reported once more
  /// with a zero wrench, so that its force can be switched off.
  struct Total {
    std::string body;
    Eigen::Vector3d force_W, torque_W;
  };
  const std::vector<Total>& totals(double t);
  bool empty() const { return wrenches_.empty() && active_.empty(); }

 private:
  std::vector<ScheduledWrench> wrenches_;
  std::vector<Total> totals_;
  std::vector<std::string> active_;  // bodies with a non-zero total at the last call
};

}  // namespace tianracer_sim

#endif  // TIANRACER_SIM_SIMULATOR_ENTITY_STATE_H
