// PhysicsWorld: N robots (URDF + Gazebo extension tags) and static shapes in a Bullet
// btMultiBodyDynamicsWorld, stepped at a fixed dt. ROS-free; Bullet stays out of this header.
//
// What Gazebo (ODE) does and how it maps here — every approximation in one place:
//  * Robots: fixed joints are merged (rigid_tree.h); each revolute/continuous/prismatic joint is a
//    btMultiBody link whose frame sits at the merged COM with principal axes (Bullet needs a
//    diagonal inertia). Self-collision is off between the links of one robot (Gazebo's default
//    <self_collide>false); robots collide with each other and with the world.
//  * Revolute/prismatic <limit lower upper> -> btMultiBodyJointLimitConstraint, solved only while
//    the joint is within 0.05 rad (or two steps of travel) of an end; continuous joints are free. <dynamics damping> is an explicit torque -d*qdot each step; <dynamics friction> is a
//    velocity motor towards 0 whose impulse is capped at friction*dt. The URDF velocity limit is
//    not enforced by the physics (ODE does not either for effort-driven joints).
//  * Friction: mu = min(mu_a, mu_b) per direction, as ODE's collide callback does (Bullet's own
//    rule would be the product: 2.0 * 100 on Gazebo's ground plane). Bullet's multibody solver
//    solves two friction rows per contact, along directions it picks itself (it overwrites any
//    set by a contact callback), and clamps them to a cone |f| <= mu N (ODE: a pyramid along
//    fdir1). Sliding along a row is exact; a diagonal slide can fall ~10% short of mu N.
//    mu1 != mu2 on a robot link uses Bullet's anisotropic friction: the collider's axis nearest
//    to fdir1 gets mu1, the other axes mu2 (an elliptic cone, exact for an axis-aligned fdir1);
//    the ratio is the link's own, a merged body takes its first such link, and static shapes
//    are isotropic. With fdir1 fixed in a spinning wheel, which direction gets mu1 turns with
//    the wheel in Gazebo too; the seed's wheels have mu1 = mu2. Rolling and spinning friction
//    are 0, restitution 0 (Gazebo's defaults).
//  * Contact softness: kp/kd become Bullet's contact stiffness/damping with ODE's combination
//    kp = 1/(1/kp_a + 1/kp_b), kd = kd_a + kd_b, which Bullet turns into the same ERP/CFM as ODE
//    (erp = dt kp/(dt kp + kd), cfm = 1/(dt kp + kd)). kp >= 1e12 (SDF's default) counts as
//    rigid: Bullet's rigid contact (erp2 of the solver) is used then. As in ODE, the CFM softens
//    only the normal rows, not friction.
//  * Penetration recovery: ODE's rule (Gazebo's ode/joints/contact.cpp). A penetrating contact
//    is pushed apart at the error-correction velocity c = erp max(depth - min_depth, 0) / dt,
//    capped at max_vel. min_depth and max_vel are the smaller of the two robot sides' <minDepth>
//    and <maxVel> (a static shape has no ODE body: its side does not count); max_vel is then
//    truncated by PhysicsOptions::contact_max_correcting_vel (100 m/s). Only c is capped, not
//    the removal of the approach velocity: an impact still stops dead. Why: Bullet's multibody
//    contacts have no cap of their own (split impulse is not implemented for multibodies and
//    m_maxErrorReduction is not read for them), so a car spawned 0.1 m into a wall left it at
//    erp2 x 0.1 m / dt = 20 m/s, spinning at 460 rad/s. Bullet gets c as a per-point ERP,
//    recomputed before every solve from the current depth. A link without <maxVel> gets
//    PhysicsOptions::contact_max_vel = 0.1 m/s, not Gazebo's 0.01: Bullet's rigid contacts
//    (erp2 0.2, ODE's rigid erp is ~1) sink 0.1-0.15 mm under a box sliding at 1 m/s, and a
//    0.01 m/s cap bound there and took 2-10 % off its friction; 0.1 m/s binds only beyond
//    0.5 mm. The cap also bounds the force a soft contact builds at rest, max_vel (dt kp + kd):
//    ~100 N for a tyre contact (see Tyres), 3.4x the front wheels' static load (Gazebo's
//    0.01 m/s on the seed's kp 1e7 wheels gives the same ~100 N); soft surfaces with kp far
//    below the seed's need a larger <maxVel> here as in Gazebo. In the tianracer's regression
//    runs the cap never binds (bit-identical figures).
//  * Tyres (not in Gazebo): a wheel contact gets one more spring-damper in series with the
//    surfaces' (PhysicsOptions::tyre_stiffness, default 1e5 N/m, critically damped for a
//    quarter of the robot's mass). Why: the seed's chassis is rigid and has no suspension, and
//    its front axle sits 1 mm above the rear; steering moves the front contact points fore and
//    aft (the wheels are offset from the kingpins), so the four contact points stop being
//    coplanar by a few tens of um. At the seed's kp (1e7 N/m: 2 um of sink) the car then stands on
//    a diagonal: in a 0.8 m turn at 0.5 m/s the outer rear wheel carried 0 N (inner 26 N) and
//    the rear axle's speed followed the loaded wheel alone (+10 % with both rear wheels at
//    v / r). ODE would do the same at that kp (its contact_surface_layer shifts every spring by
//    the same depth). A real car absorbs the warp in its tyres and suspension; 1e5 N/m lets
//    the wheels sink 0.1-0.3 mm (rolling radius unchanged: the no-slip point stays on the
//    wheel, R below the axle) and in that turn moves a rear corner's load by ~1 N of 13 N
//    instead of all of it. 0 turns it off.
//  * Collision shapes: box, sphere and cylinder primitives as themselves; meshes become convex
//    hulls shrunk by the margin (collision_margin, 0.5 mm), so the hull plus margin is the mesh's
//    own hull; static world meshes are exact triangle meshes. A mesh on the child of a continuous
//    joint that is round about the joint axis is a wheel and gets an exact fitted shape (see
//    WheelShape); wheels solve only touching contact points (no speculative ones).
//  * Only the ground plane and robots/static shapes of this world exist; there is no sleeping,
//    no threading, and the solver runs a fixed number of iterations: the same inputs give
//    bit-identical outputs.
#ifndef TIANRACER_SIM_PHYSICS_WORLD_H
#define TIANRACER_SIM_PHYSICS_WORLD_H

#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include <Eigen/Geometry>

#include "tianracer_sim/model/robot_model.h"
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
  /// ring). 0 = off, as in Gazebo. See "Tyres" at the top of this file for why.
  double tyre_stiffness = 1e5;
  double tyre_damping_ratio = 1.0;
  /// Penetration recovery (see the top of this file). contact_max_vel: a robot link's
  /// <maxVel> where its <gazebo> tag sets none (m/s; Gazebo's is 0.01, see why we differ);
  /// contact_max_correcting_vel: ODE's world cap over all contacts (Gazebo's default).
  double contact_max_vel = 0.1;
  double contact_max_correcting_vel = 100.0;
};

/// Surface of a collision (Gazebo <surface>/<gazebo reference> values; defaults are Gazebo's).
struct SurfaceParams {
  double mu1 = 1.0, mu2 = 1.0;
  double kp = 1e12, kd = 1.0;
  Eigen::Vector3d fdir1 = Eigen::Vector3d::Zero();  // in the link/shape frame; zero = none
};

/// A static body of a world (walls, boxes, cones, track meshes).
struct StaticShape {
  enum class Type { kBox, kCylinder, kSphere, kMesh, kPlane };
  std::string name;
  Type type = Type::kBox;
  /// box: full extents; cylinder: (radius, radius, length) along z; sphere: (r, r, r);
  /// plane: the normal (plane through the shape origin).
  Eigen::Vector3d size = Eigen::Vector3d::Ones();
  std::string mesh_path;  // kMesh: loaded through MeshCache::global(), used as triangles
  Eigen::Vector3d mesh_scale = Eigen::Vector3d::Ones();
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
  double motor_effort = 0.0;    // torque cap of velocity targets by default (limit or default)
};

/// Linear velocity of a frame's origin and angular velocity, both in the world frame.
struct Twist {
  Eigen::Vector3d linear = Eigen::Vector3d::Zero();
  Eigen::Vector3d angular = Eigen::Vector3d::Zero();
};

class PhysicsWorld;
struct RobotState;

/// One robot in a PhysicsWorld. Joint indices follow joints(); link names are URDF links.
/// Obtained from PhysicsWorld::robot(); valid as long as the world.
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
  /// Count of rejected (NaN/inf) commands since creation.
  std::uint64_t rejectedCommands() const;

  /// Ground truth of the root link (base_link): pose X_WB and twist of its origin, world frame.
  Eigen::Isometry3d basePose() const;
  Twist baseTwist() const;
  void setBasePose(const Eigen::Isometry3d& X_WB);
  void setBaseTwist(const Twist& twist);
  /// Spawn pose, joints at 0, all velocities and commands zero.
  void resetToSpawn();
  const Eigen::Isometry3d& spawnPose() const;

  /// All URDF link names (merged ones too), in tree order.
  const std::vector<std::string>& linkNames() const;
  /// World pose of a URDF link frame; throws PhysicsError for an unknown link.
  Eigen::Isometry3d linkPose(const std::string& link) const;

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
/// getUserIndex() = robot id (-1 for static shapes and the ground), getUserIndex2() = body
/// index in the robot's RigidTree (static: index of addStaticShape, ground: -1).

class PhysicsWorld {
 public:
  explicit PhysicsWorld(const PhysicsOptions& options = PhysicsOptions());
  ~PhysicsWorld();
  PhysicsWorld(const PhysicsWorld&) = delete;
  PhysicsWorld& operator=(const PhysicsWorld&) = delete;

  /// Adds a robot with base_link (the URDF root) at X_WB_spawn. Surfaces come from
  /// model.ext.links (mu1, mu2, kp, kd, fdir1), Gazebo's defaults where unset.
  /// Throws PhysicsError / MeshError naming the robot, link and file.
  RobotId addRobot(const RobotModel& model, const Eigen::Isometry3d& X_WB_spawn,
                   const std::string& name);
  /// Adds a static body; returns its index.
  int addStaticShape(const StaticShape& shape);

  /// Advances exactly dt: apply commands -> Bullet step (collide, solve, integrate).
  void step();

  double dt() const;
  double time() const;              // steps * dt, s
  std::uint64_t stepCount() const;
  /// Time and step count back to 0 (robots are reset separately).
  void resetTime();

  int robotCount() const;
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

/// Wheel fit of a mesh about an axis through the origin of frame B: vertices given in B.
struct WheelFit {
  bool is_wheel = false;
  double radius = 0.0;                            // max distance from the axis
  double width = 0.0;                             // extent along the axis
  Eigen::Vector3d center = Eigen::Vector3d::Zero();  // on the axis, mid-width, in B
  double roundness = 0.0;  // (min rim distance) / radius, 1 for a perfect cylinder
};
/// A mesh is a wheel when its outer vertices (distance > 0.9 R) lie within 2% of R from the
/// axis and cover every 30 degree sector around it.
WheelFit fitWheel(const std::vector<Eigen::Vector3d>& vertices_B, const Eigen::Vector3d& axis_B);

}  // namespace tianracer_sim

#endif  // TIANRACER_SIM_PHYSICS_WORLD_H
