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

/// Bullet's multibody solver, with Coulomb's cone for FrictionModel::kCone (SDF cone_model).
/// Bullet 3.24's btMultiBodyConstraintSolver::convertMultiBodyContact takes every contact's two
/// friction rows along the normal's fixed tangent basis (btPlaneSpace1: world x and y on the
/// ground) and clips their impulse pair radially to the cone mu N, each row's impulse being the
/// one that would stop the slip along it alone. A row's impulse scales with its effective mass,
/// so the clipped force of a sliding contact is not opposite to its slip: a wheel (light along
/// its rolling direction, heavy across it) resists a sideways slip ~20 times too much when the
/// basis lies along it, and a skid-steer robot turns at a rate set by its heading. With
/// set_slip_aligned(true), as Bullet's own rigid-body solver does
/// (btSequentialImpulseConstraintSolver::convertContact), a contact that slides (the impulse
/// that would stop its slip is beyond mu times its last normal impulse) gets its first row
/// along the relative tangential velocity and its second across it, so the cone's clip is mu N
/// opposite to the slip. A contact that sticks keeps the basis (its rows end inside the cone),
/// and so does one whose collider has anisotropic friction (its cone needs the axes). Off by
/// default: Gazebo's default (ODE's pyramid) holds a longitudinally sliding wheel sideways, and
/// so does the basis (docs/physics.md, Friction).
class ContactSolver : public btMultiBodyConstraintSolver {
 protected:
  btScalar solveGroupCacheFriendlySetup(btCollisionObject** bodies, int numBodies,
                                        btPersistentManifold** manifolds, int numManifolds,
                                        btTypedConstraint** constraints, int numConstraints,
                                        const btContactSolverInfo& info, btIDebugDraw* debug) override;

 public:
  void setSlipAligned(bool on) { slip_aligned_ = on; }
  bool slipAligned() const { return slip_aligned_; }

 private:
  bool slip_aligned_ = false;
  void alignFrictionWithSlip(const btContactSolverInfo& info);
  /// Turns a contact's two friction rows (multibody or static sides) to dir1, dir2.
  void turnRows(btMultiBodySolverConstraint& c1, btMultiBodySolverConstraint& c2,
                const btVector3& dir1, const btVector3& dir2, const btVector3& slip,
                const btContactSolverInfo& info);
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
