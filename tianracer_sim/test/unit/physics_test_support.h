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

/// The pose at (x, y, z) turned `yaw` about z.
inline Eigen::Isometry3d at(double x, double y, double z, double yaw = 0.0) {
  Eigen::Isometry3d X = Eigen::Isometry3d::Identity();
  X.linear() = Eigen::AngleAxisd(yaw, Eigen::Vector3d::UnitZ()).toRotationMatrix();
  X.translation() = Eigen::Vector3d(x, y, z);
  return X;
}

/// A URDF "arm": a 10 kg base_link and a 1 kg link "arm" (its COM 0.5 m out along x) on the
/// revolute joint "hinge" about y, at `hinge_xyz` on the base and yawed 0.3 rad, limited to
/// +-`limit` rad; `end` (the links and joints at the arm's end) follows.
inline std::string armRobot(const std::string& hinge_xyz, const std::string& limit,
                            const std::string& end) {
  return R"(<robot name="arm">
  <link name="base_link">
    <inertial><mass value="10"/><inertia ixx="1" ixy="0" ixz="0" iyy="1" iyz="0" izz="1"/></inertial>
  </link>
  <link name="arm">
    <inertial><origin xyz="0.5 0 0"/><mass value="1"/>
      <inertia ixx="0.001" ixy="0" ixz="0" iyy="0.02" iyz="0" izz="0.02"/></inertial>
  </link>
  <joint name="hinge" type="revolute">
    <parent link="base_link"/><child link="arm"/><origin xyz=")" +
         hinge_xyz + R"(" rpy="0 0 0.3"/>
    <axis xyz="0 1 0"/><limit lower="-)" + limit + R"(" upper=")" + limit +
         R"(" effort="5" velocity="10"/>
  </joint>
)" + end + "</robot>";
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
