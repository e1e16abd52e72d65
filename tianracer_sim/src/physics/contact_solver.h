// Internal: the contact law (contact_law.h) applied inside Bullet: the contact-added callback,
// the solver steps run before each solve, and anisotropic friction.
#ifndef TIANRACER_SIM_PHYSICS_CONTACT_SOLVER_H
#define TIANRACER_SIM_PHYSICS_CONTACT_SOLVER_H

#include "bullet.h"
#include "tianracer_sim/physics/contact_law.h"

namespace tianracer_sim {

/// Gazebo/ODE surface combination for every new or refreshed contact point; installed as
/// Bullet's (process-wide, stateless) gContactAddedCallback. Objects carry a ColliderSurfaces
/// as their user pointer.
bool onContactAdded(btManifoldPoint& cp, const btCollisionObjectWrapper* w0, int part0, int index0,
                    const btCollisionObjectWrapper* w1, int part1, int index1);

/// Bullet's multibody world with two steps added before each solve: pruneWheelManifolds and
/// capCorrection (penetration recovery).
class MultiBodyWorld : public btMultiBodyDynamicsWorld {
 public:
  using btMultiBodyDynamicsWorld::btMultiBodyDynamicsWorld;

  /// PhysicsOptions::contact_max_correcting_vel.
  double max_correcting_vel = 100.0;

  void solveConstraints(btContactSolverInfo& info) override;

 private:
  void capCorrection(const btContactSolverInfo& info);
  void pruneWheelManifolds();
};

/// The broadphase's pair filter: the collision groups and masks as Bullet's default, and two
/// bodies of one world model (user index <= -2, the same) only when either self-collides
/// (user index 3; SDF <self_collide>, Gazebo's rule). Bodies joined by a joint are in one
/// multibody, where Bullet keeps them apart.
struct WorldModelFilter : public btOverlapFilterCallback {
  bool needBroadphaseCollision(btBroadphaseProxy* p0, btBroadphaseProxy* p1) const override;
};

/// mu1 != mu2: Bullet's anisotropic friction on the object (see docs/physics.md, Friction).
void setAnisotropy(btCollisionObject* object, const ColliderSurfaces& surfaces);

}  // namespace tianracer_sim

#endif  // TIANRACER_SIM_PHYSICS_CONTACT_SOLVER_H
