// The URDF reduced to a tree of rigid bodies, the way Gazebo's URDF->SDF conversion does it:
// links joined by fixed joints are merged into one body (mass, COM and inertia combined), every
// other joint becomes a body of its own. Bullet-free, so it can be unit-tested by hand.
#ifndef TIANRACER_SIM_PHYSICS_RIGID_TREE_H
#define TIANRACER_SIM_PHYSICS_RIGID_TREE_H

#include <functional>
#include <map>
#include <stdexcept>
#include <string>
#include <vector>

#include <Eigen/Geometry>
#include <urdf_model/model.h>

#include "tianracer_sim/common/diagnostic.h"
#include "tianracer_sim/common/element_lines.h"
#include "tianracer_sim/geometry/shape.h"
#include "tianracer_sim/physics/mass_properties.h"

namespace tianracer_sim {

/// Errors while building or driving the physics (names the robot, link or joint and the value).
/// Its own type because addModelToPhysics (sim/world_physics.cpp) places physics errors at their
/// model's line and lets mesh errors through as they are.
class PhysicsError : public InputError {
 public:
  using InputError::InputError;
};

/// One <collision> element, placed in its body's frame.
struct CollisionGeometry {
  Shape shape;  // box, cylinder, sphere or mesh (mesh_path resolved); never a plane
  std::string mesh_uri;  // a mesh as written in the URDF
  std::string link;                                       // the URDF link it belongs to
  Eigen::Isometry3d X_BG = Eigen::Isometry3d::Identity();  // geometry frame in body frame B
};

enum class TreeJointType { kRevolute, kContinuous, kPrismatic };

/// A rigid body: one movable URDF link (or the root) plus every link fixed to it.
/// Its frame B is the frame of that first link.
struct TreeBody {
  std::string link;
  std::vector<std::string> merged_links;           // link first, then its fixed descendants
  std::map<std::string, Eigen::Isometry3d> X_BL;   // pose of every merged link in B
  MassProperties mass;                             // in B, about the merged COM
  std::vector<CollisionGeometry> collisions;

  // The joint to the parent body (unused for the root, parent == -1).
  int parent = -1;
  std::string joint;
  TreeJointType joint_type = TreeJointType::kContinuous;
  Eigen::Isometry3d X_PB = Eigen::Isometry3d::Identity();  // B in the parent body frame at q = 0
  Eigen::Vector3d axis_B = Eigen::Vector3d::UnitZ();        // unit joint axis in B
  bool has_position_limits = false;
  double lower = 0.0, upper = 0.0;
  double effort_limit = 0.0;    // 0 = none given
  double velocity_limit = 0.0;  // 0 = none given
  double damping = 0.0, friction = 0.0;
  /// A spring towards spring_reference: tau = -spring_stiffness (q - spring_reference)
  /// (SDF <dynamics>; URDF has none).
  double spring_stiffness = 0.0, spring_reference = 0.0;
  /// World models: collides with the other bodies of its model (SDF <self_collide>; joined
  /// bodies never collide).
  bool self_collide = false;
  /// The merged links that feel no gravity (SDF's link <gravity>false</gravity>; a robot's
  /// <gazebo reference> <gravity> or <turnGravityOff>): their mass and COM in B (mass 0: none).
  /// The physics cancels gravity on that mass at that point (Gazebo: Link::SetGravityMode).
  MassProperties gravity_free;
};

/// A robot is one tree. A world model may be a forest: every body with parent == -1 roots a
/// tree of its own (links of the model that no joint joins), simulated as a separate
/// multibody. Each tree's bodies are contiguous, its root first; a parent always precedes its
/// children. Every root's frame B is the same frame at spawn (the robot's or model's spawn
/// pose), so one spawn pose places them all.
struct RigidTree {
  std::vector<TreeBody> bodies;  // bodies[0] is the (first) root
  bool fixed_base = false;       // bodies[0] is fixed to the world (URDF: root link "world")
  /// Every URDF link -> (body index, pose of the link in that body's frame).
  std::map<std::string, std::pair<int, Eigen::Isometry3d>> links;
  /// The frame whose pose PhysicsRobot::basePose() reports: X_BM in the frame of body
  /// canonical_body (a robot: body 0 itself; a world model: its model frame, which moves with
  /// its canonical link as in Gazebo).
  int canonical_body = 0;
  Eigen::Isometry3d X_BM = Eigen::Isometry3d::Identity();
};

/// A URDF <geometry> as a Shape; a mesh's path is resolve_mesh(its URI). False for an unknown
/// type or a mesh that resolves to "".
bool shapeFromUrdf(const urdf::Geometry& geometry,
                   const std::function<std::string(const std::string&)>& resolve_mesh,
                   Shape* shape);

/// Builds the tree. Mesh URIs are resolved through `mesh_paths` (URI -> absolute path, as in
/// RobotModel), else file:// and absolute paths are taken as they are.
/// Throws PhysicsError for floating/planar joints, zero or non-finite joint axes, a movable
/// body without mass or whose inertia is not positive definite; the message names the link or
/// joint and starts with its place in `lines` ("<file>:<line>: "). A body whose principal
/// moments violate the triangle inequality is simulated as given and reported to `warn`, as
/// Gazebo does (ODE's dMassCheck asks positive definite only) and as for world models.
/// Marks `link` of `urdf` (in `tree`, built from it) as feeling no gravity: its inertial is
/// added to its body's gravity_free. A link the tree does not have is ignored.
void setLinkGravityFree(const urdf::ModelInterface& urdf, const std::string& link, RigidTree* tree);

RigidTree buildRigidTree(const urdf::ModelInterface& urdf,
                         const std::map<std::string, std::string>& mesh_paths,
                         const ElementLines& lines = ElementLines(),
                         const WarningSink& warn = WarningSink());

/// Mass properties of one URDF <inertial>, expressed in its link frame (zero mass when absent).
MassProperties linkMassProperties(const urdf::Link& link);

/// urdf::Pose -> Eigen isometry.
Eigen::Isometry3d toIsometry(const urdf::Pose& pose);

}  // namespace tianracer_sim

#endif  // TIANRACER_SIM_PHYSICS_RIGID_TREE_H
