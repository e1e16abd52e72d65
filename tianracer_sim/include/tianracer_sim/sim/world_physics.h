// A loaded world (SDF subset) into the physics: physics settings, the ground plane and the
// models' collisions.
#ifndef TIANRACER_SIM_SIM_WORLD_PHYSICS_H
#define TIANRACER_SIM_SIM_WORLD_PHYSICS_H

#include "tianracer_sim/model/robot_model.h"
#include "tianracer_sim/physics/world.h"
#include "tianracer_sim/world/world.h"

namespace tianracer_sim {

/// Physics options from the world's <physics> and ground plane (step, gravity, ground friction).
PhysicsOptions physicsOptionsFor(const WorldDescription& world, PhysicsOptions base = {});

/// Adds every collision of the world's models as a static shape. Dynamic models are added as
/// static too (the physics has no free rigid bodies yet): each is warned once by name.
/// Returns the number of shapes added.
int addWorldToPhysics(const WorldDescription& world, PhysicsWorld* physics,
                      const WarningSink& warn);

}  // namespace tianracer_sim

#endif  // TIANRACER_SIM_SIM_WORLD_PHYSICS_H
