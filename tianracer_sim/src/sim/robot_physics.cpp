#include "tianracer_sim/sim/robot_physics.h"

#include "tianracer_sim/physics/rigid_tree.h"

namespace tianracer_sim {

LinkSurfaces linkSurfaces(const RobotModel& model) {
  LinkSurfaces surfaces;
  for (const auto& [link, e] : model.ext.links) {
    SurfaceParams p;
    if (e.mu1) p.mu1 = *e.mu1;
    if (e.mu2) p.mu2 = *e.mu2;
    if (e.kp) p.kp = *e.kp;
    if (e.kd) p.kd = *e.kd;
    if (e.fdir1) p.fdir1 = *e.fdir1;
    p.max_vel = e.max_vel;
    if (e.min_depth) p.min_depth = *e.min_depth;
    surfaces[link] = p;
  }
  return surfaces;
}

RobotId addRobotModel(PhysicsWorld* physics, const RobotModel& model,
                      const Eigen::Isometry3d& X_WB_spawn, const std::string& name,
                      const WarningSink& warn) {
  if (!model.urdf) throw PhysicsError("robot '" + name + "': model has no URDF");
  RigidTree tree = buildRigidTree(*model.urdf, model.mesh_paths, model.lines, warn);
  for (const auto& [link, e] : model.ext.links) {
    if (e.gravity && !*e.gravity) setLinkGravityFree(*model.urdf, link, &tree);
  }
  return physics->addRobot(std::move(tree), linkSurfaces(model), X_WB_spawn, name);
}

}  // namespace tianracer_sim
