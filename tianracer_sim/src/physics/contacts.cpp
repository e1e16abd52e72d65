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

// Appends the contacts of the collision objects for which owns(o) holds. User indices
// (world.h): a robot's id, -1 for statics (user index 2: the static shape's index, -1 for the
// world's ground) and -2 - i for free body i; user index 2 of a body's object: the body.
template <class Owns>
void contactsOf(PhysicsWorld& world, const Owns& owns, std::vector<RobotContact>* out,
                double max_distance) {
  btDispatcher* d = world.bulletWorld()->getDispatcher();
  for (int m = 0; m < d->getNumManifolds(); ++m) {
    const btPersistentManifold* pm = d->getManifoldByIndexInternal(m);
    const btCollisionObject* o0 = pm->getBody0();
    const btCollisionObject* o1 = pm->getBody1();
    const bool own0 = owns(o0);
    const bool own1 = owns(o1);
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
    c.body = own->getUserIndex() == -1 ? -1 : own->getUserIndex2();
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

}  // namespace

void robotContacts(PhysicsWorld& world, RobotId id, std::vector<RobotContact>* out,
                   double max_distance) {
  out->clear();
  contactsOf(world, [id](const btCollisionObject* o) { return o->getUserIndex() == id; }, out,
             max_distance);
}

void freeBodyContacts(PhysicsWorld& world, int index, std::vector<RobotContact>* out,
                      double max_distance) {
  out->clear();
  const int id = -2 - index;
  contactsOf(world, [id](const btCollisionObject* o) { return o->getUserIndex() == id; }, out,
             max_distance);
}

void staticShapeContacts(PhysicsWorld& world, int index, std::vector<RobotContact>* out,
                         double max_distance) {
  contactsOf(world,
             [index](const btCollisionObject* o) {
               return o->getUserIndex() == -1 && o->getUserIndex2() == index;
             },
             out, max_distance);
}

}  // namespace tianracer_sim
