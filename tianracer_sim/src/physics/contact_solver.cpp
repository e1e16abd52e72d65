#include "contact_solver.h"

#include <algorithm>

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
