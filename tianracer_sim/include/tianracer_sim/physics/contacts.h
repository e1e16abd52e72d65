// Contacts of a robot with anything else, from the last step's contact manifolds: what a
// bumper sensor reports, for collision counts in batches and tests.
#ifndef TIANRACER_SIM_PHYSICS_CONTACTS_H
#define TIANRACER_SIM_PHYSICS_CONTACTS_H

#include <vector>

#include <Eigen/Core>

#include "tianracer_sim/physics/world.h"

namespace tianracer_sim {

/// One touching pair (a robot body and another object), at its deepest point. Identifies
/// the other object by index; names are the caller's (static shapes are nameless here).
struct RobotContact {
  int body = -1;             // body of the robot (RigidTree index); its link is bodies[body].link
  int other_robot = -1;      // another robot's id, or -1
  int other_free_body = -1;  // a free body's index, or -1
  int other_static = -1;     // a static shape's index (order of addStaticShape), or -1
  int other_body = -1;       // body index within the other robot or free body
  bool ground = false;       // the world's own ground (neither a robot nor a static shape)
  Eigen::Vector3d position_W = Eigen::Vector3d::Zero();  // on the robot's surface
  Eigen::Vector3d normal_W = Eigen::Vector3d::UnitZ();   // unit, pushing the robot out
  double depth = 0.0;    // penetration (m), >= 0
  double impulse = 0.0;  // sum of the pair's normal impulses in the last solve (N s)
};

/// Fills `out` (cleared first; no allocation once its capacity suffices) with robot `id`'s
/// contacts in the last step: points at distance <= max_distance (m). A fitted wheel touching a
/// plane (wheel on the ground) is not a contact for this purpose; a wheel against anything
/// else is.
void robotContacts(PhysicsWorld& world, RobotId id, std::vector<RobotContact>* out,
                   double max_distance = 1e-3);

/// The same for free body `index` (a world model that moves, PhysicsWorld::freeBody): `body`
/// is its body, other_* the object it touches.
void freeBodyContacts(PhysicsWorld& world, int index, std::vector<RobotContact>* out,
                      double max_distance = 1e-3);

/// The same for static shape `index` (PhysicsWorld::addStaticShape order), appended to `out`
/// (not cleared): `body` is -1, other_* what rests on or hits it. Statics touch no statics.
void staticShapeContacts(PhysicsWorld& world, int index, std::vector<RobotContact>* out,
                         double max_distance = 1e-3);

}  // namespace tianracer_sim

#endif  // TIANRACER_SIM_PHYSICS_CONTACTS_H
