#include "contact_solver.h"

#include <algorithm>
#include <tuple>

namespace tianracer_sim {

namespace {

/// The normal row as Bullet computes it from the point's flags: kp/kd (ERP/CFM from
/// stiffness and damping, as ODE) or rigid (the solver's erp2). Clears a per-point ERP/CFM
/// set by a capped earlier step (they share storage with kp/kd in btManifoldPoint).
void setNormalRow(btManifoldPoint& cp, const ContactLaw& law) {
  cp.m_contactPointFlags &= ~(BT_CONTACT_FLAG_HAS_CONTACT_ERP | BT_CONTACT_FLAG_HAS_CONTACT_CFM);
  if (law.soft) {
    cp.m_combinedContactStiffness1 = law.kp;
    cp.m_combinedContactDamping1 = law.kd;
    cp.m_contactPointFlags |= BT_CONTACT_FLAG_CONTACT_STIFFNESS_DAMPING;
  } else {
    cp.m_contactPointFlags &= ~BT_CONTACT_FLAG_CONTACT_STIFFNESS_DAMPING;
  }
}

/// Marks a point the narrowphase added or replaced in this step (a bit Bullet does not use;
/// cleared again by pruneWheelManifolds).
constexpr int kFreshContact = 1 << 20;

}  // namespace

namespace {

/// The surface index of a contact on an object: its compound child (the wrapper right below
/// the object's own), whatever a mesh below it reported as index (a triangle); 0 for an
/// object that is not a compound (one surface).
int surfaceIndex(const btCollisionObjectWrapper* w) {
  const btCollisionObjectWrapper* child = nullptr;
  for (; w->m_parent != nullptr; w = w->m_parent) child = w;
  if (child == nullptr || w->getCollisionShape()->getShapeType() != COMPOUND_SHAPE_PROXYTYPE) return 0;
  return child->m_index;
}

}  // namespace

bool onContactAdded(btManifoldPoint& cp, const btCollisionObjectWrapper* w0, int /*part0*/,
                    int /*index0*/, const btCollisionObjectWrapper* w1, int /*part1*/,
                    int /*index1*/) {
  const btCollisionObject* o0 = w0->getCollisionObject();
  const btCollisionObject* o1 = w1->getCollisionObject();
  const auto* c0 = static_cast<const ColliderSurfaces*>(o0->getUserPointer());
  const auto* c1 = static_cast<const ColliderSurfaces*>(o1->getUserPointer());
  if (c0 == nullptr || c1 == nullptr) return false;
  // Bullet's index is a triangle's for a mesh (also a GImpact mesh inside a compound): the
  // point keeps the surface's instead, for capCorrection.
  cp.m_index0 = surfaceIndex(w0);
  cp.m_index1 = surfaceIndex(w1);
  const Surface& s0 = c0->at(cp.m_index0);
  const Surface& s1 = c1->at(cp.m_index1);

  cp.m_combinedRestitution = 0.0;
  cp.m_combinedRollingFriction = 0.0;
  cp.m_combinedSpinningFriction = 0.0;

  setNormalRow(cp, contactLaw(*c0, s0, *c1, s1));
  cp.m_contactPointFlags |= kFreshContact;

  // Bullet's multibody solver recomputes the friction directions itself, so they cannot be
  // set here: the cone gets the larger coefficient, the anisotropy factors the other one.
  cp.m_combinedFriction = combinedFriction(s0, s1);
  return true;
}

void MultiBodyWorld::solveConstraints(btContactSolverInfo& info) {
  pruneWheelManifolds();
  capCorrection(info);
  btMultiBodyDynamicsWorld::solveConstraints(info);
}

/// Penetration recovery: where ODE's min_depth or max_vel would change the correction velocity,
/// the point gets its own ERP (cappedErp) and the CFM Bullet would have used; elsewhere it is
/// left exactly as the contact callback set it. Redone every step from the current depth: a
/// manifold keeps points between narrowphase refreshes, and the callback runs only when a
/// point is added or replaced.
void MultiBodyWorld::capCorrection(const btContactSolverInfo& info) {
  const double dt = info.m_timeStep;
  btDispatcher* d = getDispatcher();
  for (int m = 0; m < d->getNumManifolds(); ++m) {
    btPersistentManifold* pm = d->getManifoldByIndexInternal(m);
    const auto* c0 = static_cast<const ColliderSurfaces*>(pm->getBody0()->getUserPointer());
    const auto* c1 = static_cast<const ColliderSurfaces*>(pm->getBody1()->getUserPointer());
    if (c0 == nullptr || c1 == nullptr) continue;
    for (int p = 0; p < pm->getNumContacts(); ++p) {
      btManifoldPoint& cp = pm->getContactPoint(p);
      const bool capped = (cp.m_contactPointFlags & BT_CONTACT_FLAG_HAS_CONTACT_ERP) != 0;
      const double depth = -cp.getDistance();
      if (!(depth > 0.0) && !capped) continue;  // not penetrating, untouched
      const ContactLaw law = contactLaw(*c0, c0->at(cp.m_index0), *c1, c1->at(cp.m_index1));
      ErpCfm row{info.m_erp2, info.m_globalCfm};
      if (law.soft) row = softErpCfm(law.kp, law.kd, dt);
      const std::optional<double> erp = cappedErp(law, row.erp, depth, dt, max_correcting_vel);
      if (erp) {
        cp.m_contactERP = *erp;
        cp.m_contactCFM = row.cfm;
        cp.m_contactPointFlags |= BT_CONTACT_FLAG_HAS_CONTACT_ERP | BT_CONTACT_FLAG_HAS_CONTACT_CFM;
      } else if (capped) {
        setNormalRow(cp, law);  // back to the uncapped row (ERP/CFM overwrote kp/kd)
      }
    }
  }
}

/// A wheel's manifold keeps the points of earlier steps, which rise off the ground as the
/// wheel rolls on (16 um one step later at 1 m/s, 64 um two steps later). With rigid
/// contacts they stayed unsolved (wheel colliders solve only touching points), but a tyre
/// sinks 0.1-0.3 mm, so a few of them would still count as touching: 9 points solved per
/// step for 4 wheels instead of 4, and twice the step time. Only the narrowphase's fresh
/// point is kept: the deepest of those it found this step (on the ground, the deepest of
/// all), else the deepest of all. Not simply the deepest of all: a point keeps its normal,
/// and a stale one whose wheel has since moved the other way gets ever deeper along it (a
/// wheel spawned in a wall, pushed out through the near face while its first point still
/// pointed to the far one, hung on that point at 107 mm "deep"). (A wheel wedged between
/// two faces of one triangle mesh keeps only its deeper contact.)
void MultiBodyWorld::pruneWheelManifolds() {
  btDispatcher* d = getDispatcher();
  for (int m = 0; m < d->getNumManifolds(); ++m) {
    btPersistentManifold* pm = d->getManifoldByIndexInternal(m);
    const auto* c0 = static_cast<const ColliderSurfaces*>(pm->getBody0()->getUserPointer());
    const auto* c1 = static_cast<const ColliderSurfaces*>(pm->getBody1()->getUserPointer());
    if (!((c0 != nullptr && c0->wheel) || (c1 != nullptr && c1->wheel))) continue;
    int deepest = 0, fresh = -1;
    for (int p = 0; p < pm->getNumContacts(); ++p) {
      btManifoldPoint& cp = pm->getContactPoint(p);
      const double dist = cp.getDistance();
      if (dist < pm->getContactPoint(deepest).getDistance()) deepest = p;
      if ((cp.m_contactPointFlags & kFreshContact) &&
          (fresh < 0 || dist < pm->getContactPoint(fresh).getDistance())) {
        fresh = p;
      }
    }
    for (int p = 0; p < pm->getNumContacts(); ++p) {
      pm->getContactPoint(p).m_contactPointFlags &= ~kFreshContact;
    }
    if (pm->getNumContacts() < 2) continue;
    const btManifoldPoint keep = pm->getContactPoint(fresh >= 0 ? fresh : deepest);  // warm start
    pm->clearManifold();
    pm->addManifoldPoint(keep);
  }
}

btScalar ContactSolver::solveGroupCacheFriendlySetup(btCollisionObject** bodies, int numBodies,
                                                     btPersistentManifold** manifolds,
                                                     int numManifolds,
                                                     btTypedConstraint** constraints,
                                                     int numConstraints,
                                                     const btContactSolverInfo& info,
                                                     btIDebugDraw* debug) {
  const btScalar r = btMultiBodyConstraintSolver::solveGroupCacheFriendlySetup(
      bodies, numBodies, manifolds, numManifolds, constraints, numConstraints, info, debug);
  alignFrictionWithSlip(info);
  return r;
}

namespace {

/// The rows' (r1, r2) <- (a11 r1 + a12 r2, a21 r1 + a22 r2).
template <typename T>
void mix(T& r1, T& r2, btScalar a11, btScalar a12, btScalar a21, btScalar a22) {
  const T o1 = r1, o2 = r2;
  r1 = o1 * a11 + o2 * a12;
  r2 = o1 * a21 + o2 * a22;
}

}  // namespace

/// The rows as Bullet set them up: pairs (first, second direction) of one contact, in order,
/// each with the relative velocity along it in m_rhs = -v / (J M^-1 J^T) (friction has no
/// position error and no warm start here). With set_slip_aligned(true), a pair that slides
/// (below) is turned in the tangent plane to lie along the slip; the normal rows are untouched. A row's Jacobian,
/// its M^-1 J^T and its lever arms are linear in its direction, and the new directions are
/// combinations of the old two, so the turned rows are the same combinations of the old rows
/// (what Bullet's setupMultiBodyContactConstraint would compute along the new directions,
/// without a second pass over the multibody); a side that is a dynamic btRigidBody (none here:
/// robots and world models are multibodies, static shapes have no body) is set up again by it.
void ContactSolver::alignFrictionWithSlip(const btContactSolverInfo& info) {
  if (!slip_aligned_ || !(info.m_solverMode & SOLVER_USE_2_FRICTION_DIRECTIONS) ||
      (info.m_solverMode & SOLVER_DISABLE_VELOCITY_DEPENDENT_FRICTION_DIRECTION)) {
    return;
  }
  for (int i = 0; i + 1 < m_multiBodyFrictionContactConstraints.size(); i += 2) {
    btMultiBodySolverConstraint& c1 = m_multiBodyFrictionContactConstraints[i];
    btMultiBodySolverConstraint& c2 = m_multiBodyFrictionContactConstraints[i + 1];
    auto* cp = static_cast<btManifoldPoint*>(c1.m_originalContactPoint);
    if (cp == nullptr || c2.m_originalContactPoint != cp || c1.m_frictionIndex != c2.m_frictionIndex ||
        !(c1.m_jacDiagABInv > 0.0) || !(c2.m_jacDiagABInv > 0.0) ||
        (cp->m_contactPointFlags & BT_CONTACT_FLAG_FRICTION_ANCHOR)) {
      continue;
    }
    if (c1.m_appliedImpulse != 0.0 || c2.m_appliedImpulse != 0.0) continue;  // warm-started
    const auto collider = [](const btMultiBody* mb, int link) -> const btCollisionObject* {
      if (mb == nullptr) return nullptr;
      return link < 0 ? mb->getBaseCollider() : mb->getLinkCollider(link);
    };
    const btCollisionObject* a = collider(c1.m_multiBodyA, c1.m_linkA);
    const btCollisionObject* b = collider(c1.m_multiBodyB, c1.m_linkB);
    if ((a && a->hasAnisotropicFriction(btCollisionObject::CF_ANISOTROPIC_FRICTION)) ||
        (b && b->hasAnisotropicFriction(btCollisionObject::CF_ANISOTROPIC_FRICTION))) {
      continue;
    }
    // Sticks or slides: each row's m_rhs is the impulse that would stop the slip along it alone;
    // a contact whose friction (mu times the last step's normal impulse) can give that pair
    // sticks, and keeps Bullet's basis: its rows end inside the cone, so the basis does not
    // shape the force. Only a contact that slides gets its rows along the slip; so does one
    // that carried no load in the last step (new, or lifted), whose friction is not known.
    const btScalar stop2 = c1.m_rhs * c1.m_rhs + c2.m_rhs * c2.m_rhs;
    const btScalar hold = c1.m_friction * cp->m_appliedImpulse;
    if (hold > 0.0 && !(stop2 > hold * hold)) continue;
    const btVector3 slip = c1.m_contactNormal1 * (-c1.m_rhs / c1.m_jacDiagABInv) +
                           c2.m_contactNormal1 * (-c2.m_rhs / c2.m_jacDiagABInv);
    if (!(slip.length2() > SIMD_EPSILON)) continue;  // Bullet's threshold (convertContact)
    const btVector3 dir1 = slip.normalized();
    const btVector3 dir2 = dir1.cross(cp->m_normalWorldOnB).normalized();
    const bool rigid_a = !c1.m_multiBodyA && c1.m_solverBodyIdA >= 0 &&
                         m_tmpSolverBodyPool[c1.m_solverBodyIdA].m_originalBody != nullptr;
    const bool rigid_b = !c1.m_multiBodyB && c1.m_solverBodyIdB >= 0 &&
                         m_tmpSolverBodyPool[c1.m_solverBodyIdB].m_originalBody != nullptr;
    if (rigid_a || rigid_b) {
      btScalar relaxation;
      setupMultiBodyContactConstraint(c1, dir1, 0, *cp, info, relaxation, true);
      setupMultiBodyContactConstraint(c2, dir2, 0, *cp, info, relaxation, true);
    } else {
      turnRows(c1, c2, dir1, dir2, slip, info);
    }
    cp->m_lateralFrictionDir1 = dir1;
    cp->m_lateralFrictionDir2 = dir2;
  }
}

void ContactSolver::turnRows(btMultiBodySolverConstraint& c1, btMultiBodySolverConstraint& c2,
                             const btVector3& dir1, const btVector3& dir2, const btVector3& slip,
                             const btContactSolverInfo& info) {
  const btVector3 d1 = c1.m_contactNormal1, d2 = c2.m_contactNormal1;  // orthonormal, tangent
  const btScalar a11 = dir1.dot(d1), a12 = dir1.dot(d2), a21 = dir2.dot(d1), a22 = dir2.dot(d2);
  mix(c1.m_contactNormal1, c2.m_contactNormal1, a11, a12, a21, a22);
  mix(c1.m_contactNormal2, c2.m_contactNormal2, a11, a12, a21, a22);
  mix(c1.m_relpos1CrossNormal, c2.m_relpos1CrossNormal, a11, a12, a21, a22);
  mix(c1.m_relpos2CrossNormal, c2.m_relpos2CrossNormal, a11, a12, a21, a22);
  mix(c1.m_angularComponentA, c2.m_angularComponentA, a11, a12, a21, a22);
  mix(c1.m_angularComponentB, c2.m_angularComponentB, a11, a12, a21, a22);
  btScalar denom1 = 0.0, denom2 = 0.0;  // J M^-1 J^T of each new row
  const auto side = [&](btMultiBody* mb, int jac1, int jac2) {
    if (mb == nullptr) return;
    btScalar* j1 = &m_data.m_jacobians[jac1];
    btScalar* j2 = &m_data.m_jacobians[jac2];
    btScalar* u1 = &m_data.m_deltaVelocitiesUnitImpulse[jac1];
    btScalar* u2 = &m_data.m_deltaVelocitiesUnitImpulse[jac2];
    for (int k = 0; k < mb->getNumDofs() + 6; ++k) {
      mix(j1[k], j2[k], a11, a12, a21, a22);
      mix(u1[k], u2[k], a11, a12, a21, a22);
      denom1 += j1[k] * u1[k];
      denom2 += j2[k] * u2[k];
    }
  };
  side(c1.m_multiBodyA, c1.m_jacAindex, c2.m_jacAindex);
  side(c1.m_multiBodyB, c1.m_jacBindex, c2.m_jacBindex);
  // As setupMultiBodyContactConstraint for a friction row without an anchor: rhs = -v / (d + cfm).
  const btScalar cfm = info.m_frictionCFM / info.m_timeStep;
  for (auto [c, denom, v] : {std::make_tuple(&c1, denom1, slip.dot(dir1)),
                             std::make_tuple(&c2, denom2, slip.dot(dir2))}) {
    const btScalar d = denom + cfm;
    c->m_jacDiagABInv = d > SIMD_EPSILON ? info.m_sor / d : 0.0;
    c->m_rhs = -v * c->m_jacDiagABInv;
    c->m_cfm = cfm * c->m_jacDiagABInv;
  }
}

bool WorldModelFilter::needBroadphaseCollision(btBroadphaseProxy* p0, btBroadphaseProxy* p1) const {
  if (!(p0->m_collisionFilterGroup & p1->m_collisionFilterMask) ||
      !(p1->m_collisionFilterGroup & p0->m_collisionFilterMask)) {
    return false;
  }
  const auto* o0 = static_cast<const btCollisionObject*>(p0->m_clientObject);
  const auto* o1 = static_cast<const btCollisionObject*>(p1->m_clientObject);
  if (o0 == nullptr || o1 == nullptr) return true;
  // Gazebo's masks (ODEPhysics::Collide): no shared bit in collide_bitmask, or, when either
  // collides without contact, none in collide_without_contact_bitmask: they never meet.
  const auto* s0 = static_cast<const ColliderSurfaces*>(o0->getUserPointer());
  const auto* s1 = static_cast<const ColliderSurfaces*>(o1->getUserPointer());
  if (s0 && s1) {
    if (!(s0->collide_bitmask & s1->collide_bitmask)) return false;
    if ((s0->without_contact || s1->without_contact) &&
        !(s0->without_contact_bitmask & s1->without_contact_bitmask)) {
      return false;
    }
  }
  if (o0->getUserIndex() > -2 || o0->getUserIndex() != o1->getUserIndex()) return true;
  return o0->getUserIndex3() == 1 || o1->getUserIndex3() == 1;
}

/// Bullet scales each friction direction's components in the object's frame, which turns the
/// cone into an ellipse with semi-axes mu1 N along fdir1 and mu2 N across (cone coefficient
/// max(mu1, mu2)). Per object and per object axis: fdir1 is snapped to the nearest axis of the
/// collider (COM) frame, the first child with mu1 != mu2 decides for a merged body, and the
/// ratio is the link's own mu2/mu1 whatever the other surface.
void setAnisotropy(btCollisionObject* object, const ColliderSurfaces& surfaces) {
  for (const Surface& s : surfaces.children) {
    if (s.mu1 == s.mu2) continue;
    const double mu = std::max(s.mu1, s.mu2);
    int axis = 0;  // no fdir1: ODE picks an arbitrary direction; we take the frame's x
    if (s.has_fdir1) {
      const Eigen::Vector3d a = s.fdir1_C.cwiseAbs();
      axis = a.x() >= a.y() ? (a.x() >= a.z() ? 0 : 2) : (a.y() >= a.z() ? 1 : 2);
    }
    btVector3 f(s.mu2 / mu, s.mu2 / mu, s.mu2 / mu);
    f[axis] = s.mu1 / mu;
    object->setAnisotropicFriction(f, btCollisionObject::CF_ANISOTROPIC_FRICTION);
    return;
  }
}

}  // namespace tianracer_sim
