// PhysicsWorld: N robots (rigid trees with per-link surfaces), world models (free bodies) and
// static shapes in a Bullet btMultiBodyDynamicsWorld, stepped at a fixed dt. ROS-free; Bullet
// stays out of this header. How it maps Gazebo/ODE (joints, friction, contact softness,
// penetration recovery, tyres, collision shapes, world models, sleeping) and every
// approximation made: docs/physics.md. The contact law itself is in contact_law.h. Same
// inputs, same calls: bit-identical outputs (no threads, a fixed number of solver iterations,
// sleeping decided by the state alone).
#ifndef TIANRACER_SIM_PHYSICS_WORLD_H
#define TIANRACER_SIM_PHYSICS_WORLD_H

#include <cstdint>
#include <map>
#include <memory>
#include <string>
#include <vector>

#include <Eigen/Geometry>

#include "tianracer_sim/physics/contact_law.h"
#include "tianracer_sim/physics/rigid_tree.h"

class btMultiBodyDynamicsWorld;
class btCollisionObject;

namespace tianracer_sim {

using RobotId = int;

/// How a wheel mesh (round about its continuous joint's axis) collides. Radius R = largest vertex
/// distance from the axis, width W = extent along the axis; all shapes touch the ground exactly
/// R below the axis (Bullet's margin is kept inside the shape, never added to R).
enum class WheelShape {
  /// A disc of radius R - W/2 swept by a sphere of radius W/2 (a btCylinderShape of zero
  /// height whose margin is W/2): a tyre with a round cross-section, R and W exact. One contact
  /// point under the axle at any camber, smooth rolling, no scrub torque when steering.
  kRoundedCylinder,
  /// btCylinderShape R x W with a 0.5 mm margin: flat tread; contacts jump between the two rim
  /// edges, and steering on the spot meets scrub torque from the tread width.
  kCylinder,
  /// btSphereShape of radius R: rolls perfectly, but is 2R wide (side contacts too wide).
  kSphere,
  /// The mesh's convex hull like any other link (faceted: bumps at each facet).
  kMeshHull,
};

struct PhysicsOptions {
  double dt = 0.001;                             // s, one step
  Eigen::Vector3d gravity{0.0, 0.0, -9.8};       // Gazebo's default
  bool ground_plane = true;                      // z = 0, normal +z
  double ground_mu = 100.0, ground_mu2 = 50.0;   // Gazebo's model://ground_plane
  double ground_kp = 1e12, ground_kd = 1.0;      // SDF defaults (rigid)
  /// PGS sweeps per step. 20 keeps the parked tianracer within 0.06 mm per minute and its
  /// heading within 0.1 deg over 10 m (10 sweeps: 1.2 deg); raise it for stacked or
  /// many-contact scenes (Gazebo's and PyBullet's default is 50).
  int solver_iterations = 20;
  /// The sweeps stop early once the squared residual falls below this (0: never, except at an
  /// exact solution). A function of the state only, so still deterministic.
  double solver_residual_threshold = 0.0;
  double collision_margin = 0.0005;              // m, hulls and cylinders
  WheelShape wheel_shape = WheelShape::kRoundedCylinder;
  /// Max torque of a velocity motor on a joint whose URDF gives no effort limit (N m).
  double default_motor_effort = 10.0;
  /// Tyres (contacts of fitted wheels, i.e. WheelShape other than kMeshHull): a spring of
  /// tyre_stiffness (N/m) in series with the surfaces' kp and a damper added to their kd,
  /// 2 zeta sqrt(k m / wheels) with m the robot's mass (zeta 1: the wheel-hop mode does not
  /// ring). 0 = off, as in Gazebo. Why: docs/physics.md, Tyres.
  double tyre_stiffness = 1e5;
  double tyre_damping_ratio = 1.0;
  /// Penetration recovery (docs/physics.md). contact_max_vel: a robot link's
  /// <maxVel> where its <gazebo> tag sets none (m/s; Gazebo's is 0.01, see why we differ);
  /// contact_max_correcting_vel: ODE's world cap over all contacts (Gazebo's default).
  double contact_max_vel = 0.1;
  double contact_max_correcting_vel = 100.0;
  /// Sleeping (free bodies that allow it, PhysicsRobot::allowSleep): a body whose speeds stay
  /// below sleep_speed (|v|^2 + |w|^2 < sleep_speed^2, in m/s and rad/s) for sleep_time (s)
  /// is put to sleep: its velocities are zeroed and it costs no solver rows, no narrowphase
  /// and no AABB update until something touches it or moves it. sleep_time 0: never.
  /// Gazebo's ODE auto-disables after 1 s below 0.1 m/s and 0.1 rad/s (ODEPhysics.cc); we
  /// wait as long but for ten times slower motion, so that a slow slide or tilt is not frozen.
  double sleep_speed = 0.01;
  double sleep_time = 1.0;
};

/// Surface of each URDF link of a robot, by link name; links not listed get SurfaceParams{}.
using LinkSurfaces = std::map<std::string, SurfaceParams>;

/// A static body of a world (walls, boxes, cones, track meshes).
struct StaticShape {
  std::string name;
  /// A plane passes through the shape origin; a mesh is loaded through MeshCache::global() and
  /// used as triangles.
  Shape shape;
  Eigen::Isometry3d X_WS = Eigen::Isometry3d::Identity();
  SurfaceParams surface;
};

enum class JointType { kRevolute, kContinuous, kPrismatic };

/// A movable joint of a robot (fixed joints are merged away).
struct JointInfo {
  std::string name;
  JointType type = JointType::kContinuous;
  std::string parent_link, child_link;
  Eigen::Vector3d axis = Eigen::Vector3d::UnitZ();  // in the child link frame
  bool has_position_limits = false;
  double lower = 0.0, upper = 0.0;
  double effort_limit = 0.0;    // URDF <limit effort>; 0 = none
  double velocity_limit = 0.0;  // URDF <limit velocity>; 0 = none
  double damping = 0.0, friction = 0.0;
  /// A spring: tau = -spring_stiffness (q - spring_reference) (SDF <dynamics>).
  double spring_stiffness = 0.0, spring_reference = 0.0;
  double motor_effort = 0.0;    // torque cap of velocity targets by default (limit or default)
};

/// Linear velocity of a frame's origin and angular velocity, both in the world frame.
struct Twist {
  Eigen::Vector3d linear = Eigen::Vector3d::Zero();
  Eigen::Vector3d angular = Eigen::Vector3d::Zero();
};

class PhysicsWorld;
struct RobotState;

/// The solver's settings as Bullet holds them (get_physics_properties answers them in ODE's
/// fields: docs/gazebo_interface.md).
struct SolverSettings {
  int iterations = 0;
  double sor = 1.0;
  double residual_threshold = 0.0;
  double global_cfm = 0.0;
  double erp = 0.0;  // joint-limit and contact error reduction (btContactSolverInfo::m_erp2)
};

/// Bounds of what set_physics_properties may set.
constexpr double kMaxTimeStep = 0.1;      // s, as the node's ~max_step_size
constexpr double kMaxGravity = 1e3;       // m/s^2, each component
constexpr int kMaxSolverIterations = 10000;

/// One robot in a PhysicsWorld. Joint indices follow joints(); link names are URDF links.
/// Obtained from PhysicsWorld::robot(); valid as long as the world. Every call that moves it
/// or pushes it (poses, twists, joint states, wrenches, commands, reset) wakes it.
class PhysicsRobot {
 public:
  const std::string& name() const;
  const RigidTree& tree() const;
  const std::vector<JointInfo>& joints() const;
  /// Index into joints(), or -1.
  int jointIndex(const std::string& joint_name) const;

  double jointPosition(int i) const;  // rad or m
  double jointVelocity(int i) const;  // rad/s or m/s
  /// Effort applied during the last step: the clamped command in effort mode, the motor's
  /// torque (impulse / dt) in velocity mode, 0 otherwise.
  double jointEffort(int i) const;

  /// Effort mode: tau (clamped to +-effort_limit when that is > 0) is applied at every step
  /// until another command replaces it. Non-finite values are ignored and counted.
  void setJointEffort(int i, double tau);
  /// Velocity mode: a joint motor drives qdot to omega with at most max_effort (N m or N;
  /// < 0 = joints()[i].motor_effort), i.e. an impulse cap of max_effort * dt per step.
  void setJointVelocityTarget(int i, double omega, double max_effort = -1.0);
  /// Back to a free joint (no effort, motor off).
  void clearJointCommand(int i);
  /// Teleports one joint (set model state); velocities of other bodies are unchanged.
  void setJointState(int i, double position, double velocity);
  /// Joint properties as Gazebo's Joint::SetDamping / SetParam("friction") /
  /// SetLower/UpperLimit (what set_joint_properties changes; a velocity with fmax is
  /// setJointVelocityTarget): damping and friction >= 0 and finite; limits lower <= upper,
  /// finite, on a revolute or prismatic joint. Anything else throws PhysicsError naming the
  /// robot, joint and value, and changes nothing.
  void setJointDamping(int i, double damping);
  void setJointFriction(int i, double friction);
  void setJointLimits(int i, double lower, double upper);
  /// An effort (N m or N) added to whatever else drives joint i (Gazebo's Joint::SetForce,
  /// apply_joint_effort), at every step until replaced; 0 = none; resetToSpawn clears it.
  /// Non-finite values are rejected and counted.
  void setJointExternalEffort(int i, double effort);
  double jointExternalEffort(int i) const;
  /// Count of rejected (NaN/inf) commands since creation.
  std::uint64_t rejectedCommands() const;

  /// Ground truth of the root link (base_link): pose X_WB and twist of its origin, world frame.
  Eigen::Isometry3d basePose() const;
  Twist baseTwist() const;
  void setBasePose(const Eigen::Isometry3d& X_WB);
  /// The rigid velocity field of the model frame, joint rates kept.
  void setBaseTwist(const Twist& twist);
  /// What /gazebo/set_model_state does to a model's velocity: every link gets the twist, so the
  /// joints stop (Gazebo's Model::SetLinearVel/SetAngularVel set each link's velocity, Model.cc;
  /// gazebo_ros_api_plugin.cpp setModelState calls both). Here as a rigid motion: joint rates 0,
  /// then setBaseTwist.
  void setModelTwist(const Twist& twist);
  /// Spawn pose, joints at 0, all velocities and commands zero (free bodies: their initial pose).
  void resetToSpawn();
  const Eigen::Isometry3d& spawnPose() const;

  /// All URDF link names (merged ones too), in tree order.
  const std::vector<std::string>& linkNames() const;
  /// World pose of a URDF link frame; throws PhysicsError for an unknown link.
  Eigen::Isometry3d linkPose(const std::string& link) const;
  /// Velocity of a URDF link frame's origin and the link's angular velocity, world frame.
  Twist linkTwist(const std::string& link) const;
  /// An external force through the centre of mass of the link's body plus a torque, both in
  /// the world frame, applied at every step until replaced (zeros = none; resetToSpawn clears
  /// it). Non-finite values are rejected and counted. Throws PhysicsError for an unknown link.
  void setExternalWrench(const std::string& link, const Eigen::Vector3d& force_W,
                         const Eigen::Vector3d& torque_W);

  /// Free bodies: lets its trees without joints sleep once at rest (PhysicsOptions::sleep_*),
  /// or keeps them awake (the default). Gazebo auto-disables the links of a model that has no
  /// joints and no sensors (ODELink.cc, Init) unless <allow_auto_disable> is false. Robots
  /// never sleep.
  void allowSleep(bool allow);
  /// True when every tree of it that may sleep is asleep (false for one that may not).
  bool asleep() const;
  /// Wakes it (its sleep timer restarts).
  void wake();

  /// Contact points of the link's body with anything, at distance <= max_distance (m), from
  /// the last step's contact manifolds.
  int contactCount(const std::string& link, double max_distance = 1e-3) const;
  /// Total normal force (N) on the link's body over the contact points solved in the last
  /// step: the solver's normal impulses / dt.
  double contactNormalForce(const std::string& link) const;

  /// Energies for tests: kinetic (translation + rotation of every body), and potential
  /// -sum m g.p_com (zero at the world origin).
  double kineticEnergy() const;
  double potentialEnergy() const;
  double totalMass() const;

  /// The collision object of a link's body (for ray-cast hit lookup); may be null.
  const btCollisionObject* collisionObject(const std::string& link) const;

 private:
  friend class PhysicsWorld;
  friend struct RobotState;
  explicit PhysicsRobot(RobotState* state) : s_(state) {}
  RobotState* s_;
};

/// Where a ray/contact hit lands: btCollisionObject user indices set by the world.
/// getUserIndex() = robot id (-1 for static shapes and the ground, -2 - index for free bodies),
/// getUserIndex2() = body index in the robot's RigidTree (static: index of addStaticShape,
/// ground: -1), getUserIndex3() = 1 for a free body's self-colliding body.

class PhysicsWorld {
 public:
  explicit PhysicsWorld(const PhysicsOptions& options = PhysicsOptions());
  ~PhysicsWorld();
  PhysicsWorld(const PhysicsWorld&) = delete;
  PhysicsWorld& operator=(const PhysicsWorld&) = delete;

  /// Adds a robot (its rigid tree, buildRigidTree) with its root body's frame at X_WB_spawn;
  /// each collision gets the surface of its URDF link. Throws PhysicsError / MeshError naming
  /// the robot, link and file; on failure nothing of the robot stays in the world.
  RobotId addRobot(RigidTree tree, const LinkSurfaces& surfaces,
                   const Eigen::Isometry3d& X_WB_spawn, const std::string& name);
  /// Adds a static body; returns its index.
  int addStaticShape(const StaticShape& shape);
  /// Takes a static body out of the world (delete_model); the free bodies touching it wake.
  /// Indices of the others stay.
  void removeStaticShape(int index);
  /// Moves a static body to X_WS (an <actor>'s link, as Gazebo's SetWorldPose moves a static
  /// link: it pushes what it meets, nothing pushes it); what touches it wakes. A pose that is
  /// not finite is ignored.
  void setStaticShapePose(int index, const Eigen::Isometry3d& X_WS);

  /// Adds a world's dynamic model (a "free body"): its RigidTree, possibly a forest (links
  /// that no joint joins are separate bodies; a tree whose root is fixed to the world, as
  /// bodies[0] with fixed_base, is a fixed-base multibody), with every root's frame at X_WM
  /// and surfaces[k] for its k-th collision in body order (missing: defaults). Its meshes keep
  /// their triangles (concave, btGImpactMeshShape; a robot's are hulls). It is handled
  /// like a robot (pose of its model frame, twist, reset to X_WM, joints, link poses,
  /// contacts), except: no wheel fitting; the bodies fixed to the world are static colliders
  /// (ODE gives them no body); its bodies collide with each other only where one of them
  /// self-collides (TreeBody::self_collide; joined bodies never). Every moving body needs a
  /// positive mass and a physical inertia. Throws PhysicsError / MeshError naming the body.
  int addFreeBody(RigidTree tree, const std::vector<SurfaceParams>& surfaces,
                  const Eigen::Isometry3d& X_WM, const std::string& name);
  /// Free bodies ever added, removed ones included (their indices are never reused).
  int freeBodyCount() const;
  /// False for an index out of range or of a removed body.
  bool hasFreeBody(int index) const;
  PhysicsRobot& freeBody(int index);
  const PhysicsRobot& freeBody(int index) const;
  /// Takes the free body out of the world (delete_model); its handle becomes invalid, the
  /// other bodies keep their indices, those touching it wake.
  void removeFreeBody(int index);
  /// -1 when no free body has that name.
  int freeBodyIndex(const std::string& name) const;

  /// Advances exactly dt: apply commands -> Bullet step (collide, solve, integrate).
  void step();

  double dt() const;
  double time() const;              // steps * dt, s
  std::uint64_t stepCount() const;
  /// Time and step count back to 0 (robots are reset separately).
  void resetTime();
  /// Gazebo's SetMaxStepSize / SetGravity and ODE's "iters" and "contact_max_correcting_vel"
  /// (set_physics_properties): from the next step on. The time already run stays; a step in
  /// (0, kMaxTimeStep], finite gravity within kMaxGravity, iterations in
  /// [1, kMaxSolverIterations], a finite velocity > 0. Anything else throws PhysicsError naming
  /// the value and changes nothing.
  void setTimeStep(double dt);
  void setGravity(const Eigen::Vector3d& gravity);
  void setSolverIterations(int iterations);
  void setContactMaxCorrectingVel(double velocity);
  SolverSettings solverSettings() const;

  /// Robots ever added, removed ones included (ids are never reused).
  int robotCount() const;
  /// False for an id out of range or of a removed robot.
  bool hasRobot(RobotId id) const;
  /// Takes everything of the robot out of the world (delete_model); its handle becomes
  /// invalid, the other robots keep their ids, free bodies touching it wake.
  void removeRobot(RobotId id);
  PhysicsRobot& robot(RobotId id);
  const PhysicsRobot& robot(RobotId id) const;
  /// -1 when no robot has that name.
  RobotId robotId(const std::string& name) const;

  const PhysicsOptions& options() const;
  /// For ray casting (lidar): the Bullet world. Do not step or modify it directly.
  btMultiBodyDynamicsWorld* bulletWorld();

 private:
  friend class PhysicsRobot;
  friend struct RobotState;
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace tianracer_sim

#endif  // TIANRACER_SIM_PHYSICS_WORLD_H
