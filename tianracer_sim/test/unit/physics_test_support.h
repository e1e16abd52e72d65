// Test robots for the physics tests: a URDF and its links' surfaces, added through
// buildRigidTree + PhysicsWorld::addRobot (what sim/robot_physics.h does for a loaded model).
#ifndef TIANRACER_SIM_TEST_PHYSICS_TEST_SUPPORT_H
#define TIANRACER_SIM_TEST_PHYSICS_TEST_SUPPORT_H

#include <stdexcept>
#include <string>

#include <urdf_parser/urdf_parser.h>

#include "tianracer_sim/physics/rigid_tree.h"
#include "tianracer_sim/physics/world.h"

namespace tianracer_sim {

struct TestRobot {
  urdf::ModelInterfaceSharedPtr urdf;
  LinkSurfaces surfaces;
};

/// No ground plane, no gravity: bodies move only as the test drives them.
inline PhysicsOptions weightless() {
  PhysicsOptions o;
  o.ground_plane = false;
  o.gravity.setZero();
  return o;
}

inline TestRobot parseTestRobot(const std::string& xml) {
  TestRobot m;
  m.urdf = urdf::parseURDF(xml);
  if (!m.urdf) throw std::runtime_error("bad test URDF");
  return m;
}

inline RobotId addTestRobot(PhysicsWorld& w, const TestRobot& m, const Eigen::Isometry3d& X_WB,
                            const std::string& name) {
  return w.addRobot(buildRigidTree(*m.urdf, {}), m.surfaces, X_WB, name);
}

}  // namespace tianracer_sim

#endif  // TIANRACER_SIM_TEST_PHYSICS_TEST_SUPPORT_H
