// Internal: the state behind PhysicsWorld and PhysicsRobot, shared by world.cpp (stepping and
// the world API), robot_builder.cpp (building and removing robots) and robot.cpp (the robot API
// and command application).
#ifndef TIANRACER_SIM_PHYSICS_WORLD_IMPL_H
#define TIANRACER_SIM_PHYSICS_WORLD_IMPL_H

#include <cstdint>
#include <functional>
#include <map>
#include <memory>
#include <string>
#include <vector>

#include "bullet.h"
#include "contact_solver.h"
#include "joint_damper.h"
#include "shapes.h"
#include "tianracer_sim/physics/world.h"

namespace tianracer_sim {

struct RobotState {
  enum class Mode { kNone, kEffort, kVelocity };
  struct Command {
    Mode mode = Mode::kNone;
    double effort = 0.0;
    double velocity = 0.0;
    double max_effort = 0.0;
  };

  PhysicsWorld::Impl* world = nullptr;
  RobotId id = -1;          // robots: robot id; free bodies: free body index
  int user_index = -1;      // btCollisionObject::getUserIndex() of its colliders
  bool world_model = false;  // a free body (PhysicsWorld::addFreeBody)
  std::string name;
  RigidTree tree;
  std::vector<JointInfo> joints;
  std::map<std::string, int> joint_index;
  std::vector<std::string> link_names;
  Eigen::Isometry3d spawn = Eigen::Isometry3d::Identity();

  /// One multibody per tree of the RigidTree (a robot: one). Body b is link body_link[b] of
  /// parts[body_part[b]] (-1: that part's base); joint i moves body joint_body[i].
  struct Part {
    std::unique_ptr<btMultiBody> mb;
    int root = 0;  // body index of its base
  };
  std::vector<Part> parts;
  std::vector<int> body_part, body_link, joint_body;
  std::vector<Eigen::Isometry3d> X_BC;  // per body: COM principal frame C in body frame B
  std::vector<std::unique_ptr<btMultiBodyLinkCollider>> colliders;  // per body, may be null
  std::vector<std::unique_ptr<ColliderSurfaces>> surfaces;
  std::vector<std::unique_ptr<OwnedShape>> meshes;  // triangles of concave meshes: outlive shapes
  std::vector<std::unique_ptr<btCollisionShape>> shapes;
  /// Per joint; in the solve only for a joint with position limits, near one of them (see
  /// applyCommands). Limits, motors and dampers are made when a joint first needs them: each
  /// holds Jacobians over every degree of freedom of its multibody (Bullet's dense rows), so
  /// one of each per joint, made up front, took memory quadratic in the number of joints
  /// (6.6 GB for a chain of 20,000 links); null until then.
  std::vector<std::unique_ptr<btMultiBodyJointLimitConstraint>> limits;
  std::vector<bool> limit_in_world;
  std::vector<std::unique_ptr<btMultiBodyJointMotor>> motors;  // per joint
  std::vector<bool> motor_in_world;
  std::vector<std::unique_ptr<JointDamper>> dampers;  // per joint: damping, implicitly
  std::vector<bool> damper_in_world;
  std::vector<Command> commands;
  std::vector<double> applied_effort;
  /// Per joint: an effort added to whatever else acts (apply_joint_effort), every step until
  /// replaced; 0 = none.
  std::vector<double> ext_effort;
  std::uint64_t rejected = 0;

  // Scratch for forward kinematics (no allocation once warm).
  mutable btAlignedObjectArray<btQuaternion> scratch_q;
  mutable btAlignedObjectArray<btVector3> scratch_p;
  mutable btAlignedObjectArray<btVector3> scratch_w, scratch_v;  // compTreeLinkVelocities
  /// External wrench per body (world frame, force through the COM); applied every step.
  std::vector<Eigen::Vector3d> ext_force, ext_torque;
  bool has_ext_wrench = false;
  bool has_gravity_free = false;  // a body with TreeBody::gravity_free (applyGravityFree)
  /// Per body: the COM of its TreeBody::gravity_free mass in its COM frame C (X_BC^-1 com);
  /// set by buildRobot, used by applyGravityFree every step.
  std::vector<Eigen::Vector3d> gravity_free_com_C;

  PhysicsRobot handle{this};

  explicit RobotState() = default;
  btMultiBody* mbOfBody(int b) const { return parts[body_part[b]].mb.get(); }
  btMultiBody* mbOfJoint(int i) const { return mbOfBody(joint_body[i]); }
  /// Joint i's link index within its multibody.
  int linkOfJoint(int i) const { return body_link[joint_body[i]]; }
  /// The single multibody whose base is body 0 and whose links are bodies 1.. (robots).
  bool singleTree() const { return parts.size() == 1; }
  int bodyOf(const std::string& link) const {
    auto it = tree.links.find(link);
    if (it == tree.links.end()) {
      throw PhysicsError("robot '" + name + "': unknown link '" + link + "'");
    }
    return it->second.first;
  }
  /// World pose of body b's COM frame C (Bullet's frame for that body).
  btTransform comFrame(int b) const;
  /// World pose of body b's frame B.
  Eigen::Isometry3d bodyPose(int b) const;
  /// Velocity of the point p_W fixed to body b, and b's angular velocity (world frame).
  Twist bodyTwistAt(int b, const Eigen::Vector3d& p_W) const;
  void syncColliders();
  /// Wakes every tree that sleeps (a call moved or pushed it).
  void wake();
};

struct PhysicsWorld::Impl {
  PhysicsOptions options;
  /// Which bodies of one world model collide with each other (addFreeBody); outlives the
  /// broadphase that points to it.
  WorldModelFilter model_filter;
  std::unique_ptr<btDefaultCollisionConfiguration> config;
  std::unique_ptr<btCollisionDispatcher> dispatcher;
  std::unique_ptr<btDbvtBroadphase> broadphase;
  std::unique_ptr<btMultiBodyConstraintSolver> solver;
  std::unique_ptr<btMultiBodyDynamicsWorld> world;

  std::vector<std::unique_ptr<RobotState>> robots;
  std::vector<std::unique_ptr<RobotState>> free_bodies;  // robots without joints

  struct StaticBody {
    std::unique_ptr<btCollisionObject> object;
    OwnedShape shape;
    std::unique_ptr<ColliderSurfaces> surfaces;
  };
  std::vector<std::unique_ptr<StaticBody>> statics;
  std::unique_ptr<StaticBody> ground;

  std::uint64_t steps = 0;
  /// The time at step `step_base`: time = time_base + (steps - step_base) dt, so that a new dt
  /// (setTimeStep) changes the step from then on and not the time already run.
  double time_base = 0.0;
  std::uint64_t step_base = 0;

  explicit Impl(const PhysicsOptions& o);
  ~Impl();
  std::unique_ptr<StaticBody> makeStatic(const StaticShape& shape, int index);
  /// The surface of collision `index` (in body order) of a robot's tree.
  using SurfaceOf = std::function<const SurfaceParams&(const CollisionGeometry& g, int index)>;
  /// Builds the robot's multibody, colliders, joints, limits and motors and adds them to the
  /// world; what is added is recorded in r, so removeFromWorld can undo a partial build.
  void buildRobot(RobotState* r, const SurfaceOf& surface_of);
  /// addRobot / addFreeBody: r (with name, tree, spawn, ids set) is built into the world and
  /// appended to `list`, or nothing of it stays.
  void add(std::unique_ptr<RobotState> r, const SurfaceOf& surface_of,
           std::vector<std::unique_ptr<RobotState>>* list);
  /// Takes everything of r out of the Bullet world (constraints, colliders, multibody).
  void removeFromWorld(RobotState* r);
  void applyCommands(RobotState* r);
  void applyGravityFree(RobotState* r);
  /// Wakes the free bodies in contact with o, or with any body of r (o or r is being removed).
  void wakeTouching(const btCollisionObject* o);
  void wakeTouching(const RobotState* r);
  /// After a step: the effort each joint applied (jointEffort).
  void readEfforts(RobotState* r);
};

}  // namespace tianracer_sim

#endif  // TIANRACER_SIM_PHYSICS_WORLD_IMPL_H
