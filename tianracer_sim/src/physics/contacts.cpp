#include "tianracer_sim/physics/contacts.h"

#include <algorithm>

#include "bullet.h"
#include "tianracer_sim/physics/contact_law.h"

namespace tianracer_sim {

namespace {

bool isWheel(const btCollisionObject* o) {
  const auto* s = static_cast<const ColliderSurfaces*>(o->getUserPointer());
  return s != nullptr && s->wheel;
}

bool isPlane(const btCollisionObject* o) {
  return o->getCollisionShape() != nullptr &&
         o->getCollisionShape()->getShapeType() == STATIC_PLANE_PROXYTYPE;
}

}  // namespace

void robotContacts(PhysicsWorld& world, RobotId id, std::vector<RobotContact>* out,
                   double max_distance) {
  out->clear();
  btDispatcher* d = world.bulletWorld()->getDispatcher();
  for (int m = 0; m < d->getNumManifolds(); ++m) {
    const btPersistentManifold* pm = d->getManifoldByIndexInternal(m);
    const btCollisionObject* o0 = pm->getBody0();
    const btCollisionObject* o1 = pm->getBody1();
    // User indices (world.h): robot id, -1 for statics and the ground, -2 - i for free bodies.
    const bool own0 = o0->getUserIndex() == id;
    const bool own1 = o1->getUserIndex() == id;
    if (own0 == own1) continue;  // not ours, or a self-contact
    const btCollisionObject* own = own0 ? o0 : o1;
    const btCollisionObject* other = own0 ? o1 : o0;
    if (isWheel(own) && isPlane(other)) continue;  // wheel on the ground
    int deepest = -1;
    double impulse = 0.0;
    for (int p = 0; p < pm->getNumContacts(); ++p) {
      const btManifoldPoint& cp = pm->getContactPoint(p);
      if (cp.getDistance() > max_distance) continue;
      impulse += cp.getAppliedImpulse();
      if (deepest < 0 || cp.getDistance() < pm->getContactPoint(deepest).getDistance()) deepest = p;
    }
    if (deepest < 0) continue;
    const btManifoldPoint& cp = pm->getContactPoint(deepest);
    RobotContact c;
    c.body = own->getUserIndex2();
    const int other_index = other->getUserIndex();
    if (other_index >= 0) {
      c.other_robot = other_index;
      c.other_body = other->getUserIndex2();
    } else if (other_index <= -2) {
      c.other_free_body = -2 - other_index;
      c.other_body = other->getUserIndex2();
    } else if (other->getUserIndex2() >= 0) {
      c.other_static = other->getUserIndex2();
    } else {
      c.ground = true;
    }
    // Bullet's normal points from body1 to body0 (it is the normal on B).
    const Eigen::Vector3d n = toEigen(cp.m_normalWorldOnB);
    c.normal_W = own0 ? n : Eigen::Vector3d(-n);
    c.position_W = toEigen(own0 ? cp.getPositionWorldOnA() : cp.getPositionWorldOnB());
    c.depth = std::max(0.0, -static_cast<double>(cp.getDistance()));
    c.impulse = impulse;
    out->push_back(c);
  }
}

}  // namespace tianracer_sim
