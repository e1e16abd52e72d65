// A loaded world (SDF subset) into the physics: physics settings, the ground plane, static
// models as static shapes and dynamic models as free bodies (their links and joints as Gazebo
// simulates them); and the free bodies' link poses back into the Scene that sensors see.
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

/// Collision `c` of `link` of `model` as a static shape at the model's pose X_WM: named
/// "model::link::collision", its surface surfaceOf(c). Static models and actors (whose shapes
/// Simulator then moves each step) are made of these.
StaticShape staticShapeOf(const ModelDescription& model, const LinkDescription& link,
                          const CollisionDescription& c);

/// True for a model that never moves: <static>, no links, or every link welded to the world
/// through fixed joints (Gazebo).
bool isHeldStatic(const ModelDescription& model);

/// A dynamic world model as Gazebo simulates it, as a RigidTree in the model frame:
///  - links joined by fixed joints are one body (mass properties combined);
///  - revolute, continuous and prismatic joints are simulated, with <limit> (lower/upper,
///    effort, velocity) and <dynamics> (damping, friction, spring); a movable child's body
///    frame is its joint frame (child link frame times the joint's <pose>); other joint types
///    (ball, universal, ...) are held fixed (warned);
///  - links that no joint joins are separate bodies: each tree of the model is a multibody of
///    its own; the links joined to "world" form a fixed-base tree, which comes first;
///  - a joint that would give a link a second parent or close a loop is left out (warned);
///  - the model frame follows the canonical (first) link (RigidTree::canonical_body, X_BM);
///  - every collision with its surface (`surfaces`, in the tree's body order); plane
///    collisions are left out (warned).
/// Throws PhysicsError naming file, line, model, link and value when a link that moves has a
/// mass <= 0 or an inertia that is not positive definite, or its body's inertia is not
/// physical.
RigidTree worldModelTree(const WorldDescription& world, const ModelDescription& model,
                         std::vector<SurfaceParams>* surfaces, const WarningSink& warn);

/// Adds the world's models: static ones (isHeldStatic) as static shapes, dynamic ones as free
/// bodies named after the model (worldModelTree), which may sleep at rest when the model has
/// no joints and allows it (<allow_auto_disable>). A dynamic model whose mass properties are
/// bad is warned about and added as a static one: the rest of the world loads. Returns the
/// number of collision shapes added. Throws PhysicsError / MeshError naming the model.
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
/// to that link's pose (each link of a model moves on its own; robots' bodies are left alone).
/// Call before sensing.
void updateFreeBodyScene(const PhysicsWorld& physics, Scene* scene);

}  // namespace tianracer_sim

#endif  // TIANRACER_SIM_SIM_WORLD_PHYSICS_H
