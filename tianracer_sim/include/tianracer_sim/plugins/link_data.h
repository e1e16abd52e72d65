// What sensor cores read about a link from the simulation, whichever model carries it: its
// state (pose and velocities) and its contacts. ROS-free plain data.
#ifndef TIANRACER_SIM_PLUGINS_LINK_DATA_H
#define TIANRACER_SIM_PLUGINS_LINK_DATA_H

#include <string>

#include <Eigen/Geometry>

namespace tianracer_sim {

/// A link's pose and its velocities in the world frame.
struct LinkState {
  Eigen::Isometry3d X_WL = Eigen::Isometry3d::Identity();
  Eigen::Vector3d v_W = Eigen::Vector3d::Zero();  // of the link frame's origin
  Eigen::Vector3d w_W = Eigen::Vector3d::Zero();
};

/// One contact point of a link with something else, named as Gazebo names collisions
/// ("model::link", "model::link::collision").
struct LinkContact {
  std::string own;    // the link's side
  std::string other;  // what it touches
  Eigen::Vector3d position_W = Eigen::Vector3d::Zero();
  Eigen::Vector3d normal_W = Eigen::Vector3d::UnitZ();  // unit, pushing the link out
  double depth = 0.0;
  double impulse = 0.0;  // N s over the step
};

}  // namespace tianracer_sim

#endif  // TIANRACER_SIM_PLUGINS_LINK_DATA_H
