// A loaded world (SDF subset) into the physics: physics settings, the ground plane, static
// models as static shapes and dynamic models as free rigid bodies; and the free bodies' poses
// back into the Scene that sensors see.
#ifndef TIANRACER_SIM_SIM_WORLD_PHYSICS_H
#define TIANRACER_SIM_SIM_WORLD_PHYSICS_H

#include <vector>

#include "tianracer_sim/model/robot_model.h"
#include "tianracer_sim/physics/world.h"
#include "tianracer_sim/scene/scene.h"
#include "tianracer_sim/world/world.h"

namespace tianracer_sim {

/// Physics options from the world's <physics> and ground plane (step, gravity, ground friction).
PhysicsOptions physicsOptionsFor(const WorldDescription& world, PhysicsOptions base = {});

/// The surface of a world collision: <friction><ode> mu/mu2 and <contact><ode>
/// kp/kd/max_vel/min_depth (unset: SurfaceParams' defaults).
SurfaceParams surfaceOf(const CollisionDescription& c);

/// A dynamic model as one rigid body in the model frame: its links merged (mass properties
/// combined, Gazebo's fixed-joint reduction), every collision with its surface (`surfaces`
/// in the order of the tree's collisions). Joints other than fixed, and links joined by no
/// joint, are held fixed too: each is warned once. Plane collisions are skipped (warned).
RigidTree freeBodyTree(const WorldDescription& world, const ModelDescription& model,
                       std::vector<SurfaceParams>* surfaces, const WarningSink& warn);

/// Adds the world's models: static ones (and models fixed to "world" by a joint) as static
/// shapes, dynamic ones as free bodies named after the model. Returns the number of collision
/// shapes added. Throws PhysicsError / MeshError naming the model.
int addWorldToPhysics(const WorldDescription& world, PhysicsWorld* physics,
                      const WarningSink& warn);

/// What addModelToPhysics added for one model: its free body, or its static shapes.
struct WorldModelBodies {
  int free_body = -1;
  std::vector<int> statics;
  int shapes = 0;  // collision shapes added
};

/// Adds one model of `world` as addWorldToPhysics does (spawn_sdf_model reuses it). On a throw
/// nothing of the model stays in the physics.
WorldModelBodies addModelToPhysics(const WorldDescription& world, const ModelDescription& model,
                                   PhysicsWorld* physics, const WarningSink& warn);

/// Takes out what addModelToPhysics added (delete_model).
void removeModelFromPhysics(const WorldModelBodies& bodies, PhysicsWorld* physics);

/// Moves every non-static scene body "<model>::<link>" whose model is a free body of `physics`
/// to that link's pose (robots' bodies are left alone). Call before sensing.
void updateFreeBodyScene(const PhysicsWorld& physics, Scene* scene);

}  // namespace tianracer_sim

#endif  // TIANRACER_SIM_SIM_WORLD_PHYSICS_H
