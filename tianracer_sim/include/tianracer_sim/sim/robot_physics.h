// A loaded robot (URDF + Gazebo tags) into the physics: its rigid tree and each link's surface
// from the <gazebo reference> tags (mu1, mu2, kp, kd, fdir1, maxVel, minDepth).
#ifndef TIANRACER_SIM_SIM_ROBOT_PHYSICS_H
#define TIANRACER_SIM_SIM_ROBOT_PHYSICS_H

#include <string>

#include "tianracer_sim/model/robot_model.h"
#include "tianracer_sim/physics/world.h"

namespace tianracer_sim {

/// The surfaces the model's Gazebo tags set; unset values keep SurfaceParams' (Gazebo's) defaults.
LinkSurfaces linkSurfaces(const RobotModel& model);

/// buildRigidTree + linkSurfaces + PhysicsWorld::addRobot. Throws PhysicsError / MeshError
/// naming the robot, link and file ("<file>:<line>: " of the link or joint at fault); what is
/// simulated as given (inertia breaking the triangle inequality) goes to `warn`.
RobotId addRobotModel(PhysicsWorld* physics, const RobotModel& model,
                      const Eigen::Isometry3d& X_WB_spawn, const std::string& name,
                      const WarningSink& warn = WarningSink());

}  // namespace tianracer_sim

#endif  // TIANRACER_SIM_SIM_ROBOT_PHYSICS_H
