#include "tianracer_sim/physics/world.h"

#include <algorithm>
#include <cassert>
#include <cmath>
#include <limits>
#include <map>
#include <sstream>

// Bullet's headers trip -Wunused-parameter; keep our own warnings meaningful.
#pragma GCC diagnostic push
#pragma GCC diagnostic ignored "-Wunused-parameter"
#include <btBulletDynamicsCommon.h>
#include <BulletDynamics/Featherstone/btMultiBody.h>
#include <BulletDynamics/Featherstone/btMultiBodyConstraintSolver.h>
#include <BulletDynamics/Featherstone/btMultiBodyDynamicsWorld.h>
#include <BulletDynamics/Featherstone/btMultiBodyJointLimitConstraint.h>
#include <BulletDynamics/Featherstone/btMultiBodyJointMotor.h>
#include <BulletDynamics/Featherstone/btMultiBodyLinkCollider.h>
#include <LinearMath/btConvexHullComputer.h>
#pragma GCC diagnostic pop

#include "tianracer_sim/mesh/mesh_loader.h"

#ifndef BT_USE_DOUBLE_PRECISION
#error "tianracer_sim_physics needs double-precision Bullet (pkg-config bullet-float64)"
#endif

namespace tianracer_sim {

namespace {

btVector3 toBt(const Eigen::Vector3d& v) { return btVector3(v.x(), v.y(), v.z()); }
Eigen::Vector3d toEigen(const btVector3& v) { return Eigen::Vector3d(v.x(), v.y(), v.z()); }

btTransform toBt(const Eigen::Isometry3d& X) {
  const Eigen::Matrix3d& R = X.linear();
  btMatrix3x3 basis(R(0, 0), R(0, 1), R(0, 2), R(1, 0), R(1, 1), R(1, 2), R(2, 0), R(2, 1),
                    R(2, 2));
  return btTransform(basis, toBt(Eigen::Vector3d(X.translation())));
}

Eigen::Isometry3d toEigen(const btTransform& t) {
  Eigen::Isometry3d X = Eigen::Isometry3d::Identity();
  const btMatrix3x3& B = t.getBasis();
  for (int r = 0; r < 3; ++r) {
    for (int c = 0; c < 3; ++c) X.linear()(r, c) = B[r][c];
  }
  X.translation() = toEigen(t.getOrigin());
  return X;
}

btQuaternion toBtQuat(const Eigen::Matrix3d& R) {
  const Eigen::Quaterniond q(R);
  return btQuaternion(q.x(), q.y(), q.z(), q.w());
}

/// A rotation taking +Y to `axis` (unit), for Bullet's Y-up cylinders.
Eigen::Matrix3d rotationYTo(const Eigen::Vector3d& axis) {
  return Eigen::Quaterniond::FromTwoVectors(Eigen::Vector3d::UnitY(), axis).toRotationMatrix();
}

// ---------------------------------------------------------------------------------------------
// Surfaces and the contact callback.

constexpr double kRigidKp = 1e12;  // SDF's default kp: treated as a rigid contact

struct Surface {
  double mu1 = 1.0, mu2 = 1.0, kp = 1e12, kd = 1.0;
  double max_vel = 0.1, min_depth = 0.0;  // robots only; max_vel infinite: the world's cap
  bool has_fdir1 = false;
  btVector3 fdir1_C{0, 0, 0};  // in the collision object's frame
};

/// What btCollisionObject::getUserPointer() points to: one surface per compound child (index),
/// or a single one for non-compound objects.
struct ColliderSurfaces {
  std::vector<Surface> children;
  // A robot's body (ODE would give it a body; static shapes have none).
  bool robot = false;
  // A collider whose shapes are all fitted wheels has a tyre (PhysicsOptions::tyre_*).
  bool wheel = false;
  double tyre_stiffness = 0.0, tyre_damping = 0.0;
  const Surface& at(int index) const {
    return (index >= 0 && index < static_cast<int>(children.size())) ? children[index] : children[0];
  }
};

Surface toSurface(const SurfaceParams& p, const Eigen::Matrix3d& R_CL) {
  Surface s;
  s.mu1 = std::max(0.0, p.mu1);
  s.mu2 = std::max(0.0, p.mu2);
  s.kp = p.kp > 0.0 ? p.kp : kRigidKp;
  s.kd = std::max(0.0, p.kd);
  if (p.fdir1.allFinite() && p.fdir1.norm() > 1e-9) {
    s.has_fdir1 = true;
    s.fdir1_C = toBt(R_CL * p.fdir1.normalized());
  }
  return s;
}

SurfaceParams surfaceOfLink(const RobotModel& model, const std::string& link) {
  SurfaceParams p;  // Gazebo defaults: mu 1, kp 1e12, kd 1
  auto it = model.ext.links.find(link);
  if (it == model.ext.links.end()) return p;
  const LinkExtension& e = it->second;
  if (e.mu1) p.mu1 = *e.mu1;
  if (e.mu2) p.mu2 = *e.mu2;
  if (e.kp) p.kp = *e.kp;
  if (e.kd) p.kd = *e.kd;
  if (e.fdir1) p.fdir1 = *e.fdir1;
  return p;
}

/// A robot link's <maxVel> and <minDepth> (penetration recovery, world.h); a negative maxVel
/// means the world's cap, as in Gazebo.
void setRecovery(const RobotModel& model, const std::string& link, const PhysicsOptions& options,
                 Surface* s) {
  s->max_vel = options.contact_max_vel;
  s->min_depth = 0.0;
  auto it = model.ext.links.find(link);
  if (it == model.ext.links.end()) return;
  if (it->second.max_vel) s->max_vel = *it->second.max_vel;
  if (it->second.min_depth) s->min_depth = std::max(0.0, *it->second.min_depth);
  if (!(s->max_vel >= 0.0)) s->max_vel = std::numeric_limits<double>::infinity();
}

/// How the normal row of one contact behaves (see world.h, "Contact softness", "Tyres" and
/// "Penetration recovery"): everything but the time step and the world's cap.
struct ContactLaw {
  bool soft = false;             // kp/kd below: Bullet's stiffness/damping; else rigid (erp2)
  double kp = 0.0, kd = 0.0;     // with the tyre, if any
  double max_vel = std::numeric_limits<double>::infinity();  // robot sides' (m/s)
  double min_depth = 0.0;        // depth left uncorrected (m)
};

ContactLaw contactLaw(const ColliderSurfaces& c0, const Surface& s0, const ColliderSurfaces& c1,
                      const Surface& s1) {
  ContactLaw law;
  // Stiffness: springs in series, dampers in parallel (ODE's rule); a tyre (on one side only:
  // a wheel on a wheel is left to the surfaces) is one more spring and damper of the same kind.
  law.kp = 1.0 / (1.0 / s0.kp + 1.0 / s1.kp);
  law.kd = s0.kd + s1.kd;
  if (c0.wheel != c1.wheel) {
    const ColliderSurfaces& tyre = c0.wheel ? c0 : c1;
    if (tyre.tyre_stiffness > 0.0) {
      law.kp = 1.0 / (1.0 / law.kp + 1.0 / tyre.tyre_stiffness);
      law.kd += tyre.tyre_damping;
    }
  }
  law.soft = law.kp < 0.5 * kRigidKp;
  // ODE/Gazebo: max_vel and min_depth of the bodies (the smaller of two); static shapes have
  // no ODE body.
  bool first = true;
  for (const auto& side : {std::make_pair(&c0, &s0), std::make_pair(&c1, &s1)}) {
    if (!side.first->robot) continue;
    law.max_vel = std::min(law.max_vel, side.second->max_vel);
    law.min_depth = first ? side.second->min_depth : std::min(law.min_depth, side.second->min_depth);
    first = false;
  }
  return law;
}

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

/// Gazebo/ODE surface combination for every new or refreshed contact point (see world.h).
bool onContactAdded(btManifoldPoint& cp, const btCollisionObjectWrapper* w0, int /*part0*/,
                    int index0, const btCollisionObjectWrapper* w1, int /*part1*/, int index1) {
  const btCollisionObject* o0 = w0->getCollisionObject();
  const btCollisionObject* o1 = w1->getCollisionObject();
  const auto* c0 = static_cast<const ColliderSurfaces*>(o0->getUserPointer());
  const auto* c1 = static_cast<const ColliderSurfaces*>(o1->getUserPointer());
  if (c0 == nullptr || c1 == nullptr) return false;
  const Surface& s0 = c0->at(index0);
  const Surface& s1 = c1->at(index1);

  cp.m_combinedRestitution = 0.0;
  cp.m_combinedRollingFriction = 0.0;
  cp.m_combinedSpinningFriction = 0.0;

  setNormalRow(cp, contactLaw(*c0, s0, *c1, s1));
  cp.m_contactPointFlags |= kFreshContact;

  // Friction: ODE takes the minimum per direction; the cone gets the larger of the two and
  // the collider's anisotropic-friction factors (set at build time) shrink the other one.
  // Bullet's multibody solver recomputes the friction directions itself, so they cannot be
  // set here.
  cp.m_combinedFriction = std::max(std::min(s0.mu1, s1.mu1), std::min(s0.mu2, s1.mu2));

  return true;
}

/// Bullet's multibody world with two steps added before each solve (pruneWheelManifolds,
/// capCorrection).
class MultiBodyWorld : public btMultiBodyDynamicsWorld {
 public:
  using btMultiBodyDynamicsWorld::btMultiBodyDynamicsWorld;

  /// PhysicsOptions::contact_max_correcting_vel.
  double max_correcting_vel = 100.0;

  void solveConstraints(btContactSolverInfo& info) override {
    pruneWheelManifolds();
    capCorrection(info);
    btMultiBodyDynamicsWorld::solveConstraints(info);
  }

 private:
  /// Penetration recovery (world.h): Bullet pushes a penetrating point apart at
  /// c = erp depth / dt with no cap. Where ODE's min_depth or max_vel would change c, the point
  /// gets its own ERP, erp' = min(erp (depth - min_depth), max_vel dt) / depth, and the CFM
  /// Bullet would have used; elsewhere it is left exactly as the contact callback set it.
  /// Redone every step from the current depth: a manifold keeps points between narrowphase
  /// refreshes, and the callback runs only when a point is added or replaced.
  void capCorrection(const btContactSolverInfo& info) {
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
        double erp = info.m_erp2, cfm = info.m_globalCfm;
        if (law.soft) {  // as btMultiBodyConstraintSolver::setupMultiBodyContactConstraint
          const double denom = std::max(dt * law.kp + law.kd, double(SIMD_EPSILON));
          cfm = 1.0 / denom;
          erp = dt * law.kp / denom;
        }
        const double cap = std::min(law.max_vel, max_correcting_vel);
        if (depth > 0.0 && (law.min_depth > 0.0 || erp * depth > cap * dt)) {
          cp.m_contactERP = std::min(erp * std::max(depth - law.min_depth, 0.0), cap * dt) / depth;
          cp.m_contactCFM = cfm;
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
  void pruneWheelManifolds() {
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
};

/// mu1 != mu2: Bullet's anisotropic friction scales each friction direction's components in the
/// object's frame, which turns the friction cone into an ellipse with semi-axes mu1 N along
/// fdir1 and mu2 N across (with the cone coefficient max(mu1, mu2)). It is per object and per
/// object axis: fdir1 is snapped to the nearest axis of the collider (COM) frame (exact for
/// the usual axis-aligned fdir1), the first child with mu1 != mu2 decides for a merged body,
/// and the ratio is the link's own mu2/mu1 whatever the other surface. Robots only.
void setAnisotropy(btCollisionObject* object, const ColliderSurfaces& surfaces) {
  for (const Surface& s : surfaces.children) {
    if (s.mu1 == s.mu2) continue;
    const double mu = std::max(s.mu1, s.mu2);
    int axis = 0;  // no fdir1: ODE picks an arbitrary direction; we take the frame's x
    if (s.has_fdir1) {
      const btVector3 a = s.fdir1_C.absolute();
      axis = a.x() >= a.y() ? (a.x() >= a.z() ? 0 : 2) : (a.y() >= a.z() ? 1 : 2);
    }
    btVector3 f(s.mu2 / mu, s.mu2 / mu, s.mu2 / mu);
    f[axis] = s.mu1 / mu;
    object->setAnisotropicFriction(f, btCollisionObject::CF_ANISOTROPIC_FRICTION);
    return;
  }
}

// ---------------------------------------------------------------------------------------------
// Shapes.

/// Convex hull of `points` whose faces are moved inwards by `margin`, so that hull + margin is
/// the original hull (Bullet adds the margin outwards; its default 4 cm would swallow a wheel).
std::unique_ptr<btConvexHullShape> makeHull(const std::vector<btVector3>& points, double margin) {
  btConvexHullComputer hc;
  const double shrunk = hc.compute(&points[0].x(), sizeof(btVector3), static_cast<int>(points.size()),
                                   margin, 0.25);
  auto hull = std::make_unique<btConvexHullShape>();
  if (shrunk >= 0.0 && hc.vertices.size() >= 4) {
    for (int i = 0; i < hc.vertices.size(); ++i) hull->addPoint(hc.vertices[i], false);
    hull->setMargin(std::max(shrunk, 1e-6));
  } else {  // degenerate (flat) mesh: keep the points, accept a margin-thick inflation
    for (const auto& p : points) hull->addPoint(p, false);
    hull->setMargin(margin);
  }
  hull->recalcLocalAabb();
  hull->optimizeConvexHull();
  return hull;
}

}  // namespace

WheelFit fitWheel(const std::vector<Eigen::Vector3d>& vertices_B, const Eigen::Vector3d& axis_B) {
  WheelFit fit;
  if (vertices_B.size() < 6 || !(axis_B.norm() > 0.0)) return fit;
  const Eigen::Vector3d a = axis_B.normalized();
  double amin = std::numeric_limits<double>::infinity(), amax = -amin, rmax = 0.0;
  for (const auto& v : vertices_B) {
    const double s = v.dot(a);
    amin = std::min(amin, s);
    amax = std::max(amax, s);
    rmax = std::max(rmax, (v - s * a).norm());
  }
  if (!(rmax > 0.0)) return fit;
  // Outer vertices must go all the way round the axis: 12 sectors of 30 degrees.
  const Eigen::Vector3d e1 = a.unitOrthogonal(), e2 = a.cross(e1);
  constexpr int kSectors = 12;
  double sector_r[kSectors] = {0};
  for (const auto& v : vertices_B) {
    const Eigen::Vector3d r = v - v.dot(a) * a;
    const double ang = std::atan2(r.dot(e2), r.dot(e1));
    int k = static_cast<int>(std::floor((ang + M_PI) / (2.0 * M_PI) * kSectors));
    k = std::min(std::max(k, 0), kSectors - 1);
    sector_r[k] = std::max(sector_r[k], r.norm());
  }
  fit.roundness = *std::min_element(sector_r, sector_r + kSectors) / rmax;
  fit.radius = rmax;
  fit.width = amax - amin;
  fit.center = 0.5 * (amin + amax) * a;
  fit.is_wheel = fit.roundness > 0.98 && fit.width > 0.0;
  return fit;
}

// ---------------------------------------------------------------------------------------------

struct RobotState {
  enum class Mode { kNone, kEffort, kVelocity };
  struct Command {
    Mode mode = Mode::kNone;
    double effort = 0.0;
    double velocity = 0.0;
    double max_effort = 0.0;
  };

  PhysicsWorld::Impl* world = nullptr;
  RobotId id = -1;
  std::string name;
  RigidTree tree;
  std::vector<JointInfo> joints;
  std::map<std::string, int> joint_index;
  std::vector<std::string> link_names;
  Eigen::Isometry3d spawn = Eigen::Isometry3d::Identity();

  std::unique_ptr<btMultiBody> mb;
  std::vector<Eigen::Isometry3d> X_BC;  // per body: COM principal frame C in body frame B
  std::vector<std::unique_ptr<btMultiBodyLinkCollider>> colliders;  // per body, may be null
  std::vector<std::unique_ptr<ColliderSurfaces>> surfaces;
  std::vector<std::unique_ptr<btCollisionShape>> shapes;
  std::vector<std::unique_ptr<btMultiBodyJointLimitConstraint>> limits;
  std::vector<int> limit_joint;       // joint index of each limit
  std::vector<bool> limit_in_world;   // added only near the limit (see applyCommands)
  std::vector<std::unique_ptr<btMultiBodyJointMotor>> motors;  // per joint
  std::vector<bool> motor_in_world;
  std::vector<Command> commands;
  std::vector<double> applied_effort;
  std::uint64_t rejected = 0;

  // Scratch for forward kinematics (no allocation once warm).
  mutable btAlignedObjectArray<btQuaternion> scratch_q;
  mutable btAlignedObjectArray<btVector3> scratch_p;

  PhysicsRobot handle{this};

  explicit RobotState() = default;
  int bodyOf(const std::string& link) const {
    auto it = tree.links.find(link);
    if (it == tree.links.end()) {
      throw PhysicsError("robot '" + name + "': unknown link '" + link + "'");
    }
    return it->second.first;
  }
  /// World pose of body b's COM frame C (Bullet's frame for that body).
  btTransform comFrame(int b) const;
  void syncColliders();
};

struct PhysicsWorld::Impl {
  PhysicsOptions options;
  std::unique_ptr<btDefaultCollisionConfiguration> config;
  std::unique_ptr<btCollisionDispatcher> dispatcher;
  std::unique_ptr<btDbvtBroadphase> broadphase;
  std::unique_ptr<btMultiBodyConstraintSolver> solver;
  std::unique_ptr<btMultiBodyDynamicsWorld> world;

  std::vector<std::unique_ptr<RobotState>> robots;

  struct StaticBody {
    std::unique_ptr<btCollisionObject> object;
    std::unique_ptr<btCollisionShape> shape;
    std::unique_ptr<btTriangleIndexVertexArray> mesh_interface;
    std::vector<btScalar> mesh_vertices;
    std::vector<int> mesh_indices;
    std::unique_ptr<ColliderSurfaces> surfaces;
  };
  std::vector<std::unique_ptr<StaticBody>> statics;
  std::unique_ptr<StaticBody> ground;

  std::uint64_t steps = 0;

  explicit Impl(const PhysicsOptions& o);
  ~Impl();
  std::unique_ptr<StaticBody> makeStatic(const StaticShape& shape, int index);
  void buildRobot(RobotState* r, const RobotModel& model);
  std::unique_ptr<btCollisionShape> makeRobotShape(const RobotState& r, const TreeBody& body,
                                                   const CollisionGeometry& g,
                                                   Eigen::Isometry3d* X_BS, bool* is_wheel);
  void applyCommands(RobotState* r);
};

PhysicsWorld::Impl::Impl(const PhysicsOptions& o) : options(o) {
  if (!(options.dt > 0.0) || !std::isfinite(options.dt)) {
    throw PhysicsError("physics: dt must be positive, got " + std::to_string(options.dt));
  }
  if (options.solver_iterations < 1) {
    throw PhysicsError("physics: solver_iterations must be >= 1");
  }
  if (!(options.tyre_stiffness >= 0.0) || !std::isfinite(options.tyre_stiffness) ||
      !(options.tyre_damping_ratio >= 0.0) || !std::isfinite(options.tyre_damping_ratio)) {
    throw PhysicsError("physics: tyre_stiffness and tyre_damping_ratio must be finite and >= 0, got " +
                       std::to_string(options.tyre_stiffness) + " and " +
                       std::to_string(options.tyre_damping_ratio));
  }
  if (!(options.contact_max_vel >= 0.0) || !(options.contact_max_correcting_vel > 0.0)) {
    throw PhysicsError("physics: contact_max_vel must be >= 0 and contact_max_correcting_vel > 0, got " +
                       std::to_string(options.contact_max_vel) + " and " +
                       std::to_string(options.contact_max_correcting_vel));
  }
  config = std::make_unique<btDefaultCollisionConfiguration>();
  dispatcher = std::make_unique<btCollisionDispatcher>(config.get());
  broadphase = std::make_unique<btDbvtBroadphase>();
  solver = std::make_unique<btMultiBodyConstraintSolver>();
  auto mbw = std::make_unique<MultiBodyWorld>(dispatcher.get(), broadphase.get(), solver.get(),
                                              config.get());
  mbw->max_correcting_vel = options.contact_max_correcting_vel;
  world = std::move(mbw);
  world->setGravity(toBt(options.gravity));
  // Static shapes never move: their AABBs are computed once, when added (below they are put
  // to ISLAND_SLEEPING, as Bullet does for static rigid bodies). Updating them every step
  // cost about 7 % of a step on the racetrack and kept moving their broadphase proxies from
  // the fixed to the dynamic tree and back.
  world->setForceUpdateAllAabbs(false);
  // Not m_deterministicOverlappingPairs: it sorts a fresh copy of the pair array every step
  // (one allocation per step). Pair order already follows the order of insertions, which is
  // the same for the same sequence of calls.

  btContactSolverInfo& si = world->getSolverInfo();
  si.m_numIterations = options.solver_iterations;
  si.m_leastSquaresResidualThreshold = options.solver_residual_threshold;
  // Two friction directions per contact (one would let the car slide sideways), no random
  // order.
  // Warm-starting the joint motors/limits too (not only contacts) halves the creep of a car
  // parked on its velocity motors: 2.5 -> 1.3 um/s at 50 iterations.
  si.m_solverMode = SOLVER_USE_WARMSTARTING | SOLVER_USE_ARTICULATED_WARMSTARTING |
                    SOLVER_USE_2_FRICTION_DIRECTIONS | SOLVER_SIMD;
  si.m_timeStep = options.dt;

  // Process-wide in Bullet; the function is stateless (surfaces hang off the objects).
  gContactAddedCallback = &onContactAdded;

  if (options.ground_plane) {
    StaticShape g;
    g.name = "ground_plane";
    g.type = StaticShape::Type::kPlane;
    g.size = Eigen::Vector3d::UnitZ();
    g.surface.mu1 = options.ground_mu;
    g.surface.mu2 = options.ground_mu2;
    g.surface.kp = options.ground_kp;
    g.surface.kd = options.ground_kd;
    ground = makeStatic(g, -1);
  }
}

PhysicsWorld::Impl::~Impl() {
  for (auto& r : robots) {
    for (std::size_t j = 0; j < r->motors.size(); ++j) {
      if (r->motor_in_world[j]) world->removeMultiBodyConstraint(r->motors[j].get());
    }
    for (std::size_t k = 0; k < r->limits.size(); ++k) {
      if (r->limit_in_world[k]) world->removeMultiBodyConstraint(r->limits[k].get());
    }
    for (auto& c : r->colliders) {
      if (c) world->removeCollisionObject(c.get());
    }
    world->removeMultiBody(r->mb.get());
  }
  for (auto& s : statics) world->removeCollisionObject(s->object.get());
  if (ground) world->removeCollisionObject(ground->object.get());
  robots.clear();
  statics.clear();
  ground.reset();
  world.reset();
}

std::unique_ptr<PhysicsWorld::Impl::StaticBody> PhysicsWorld::Impl::makeStatic(
    const StaticShape& s, int index) {
  auto body = std::make_unique<StaticBody>();
  const double margin = options.collision_margin;
  const std::string what = "static shape '" + s.name + "'";
  if (!s.size.allFinite()) throw PhysicsError(what + ": non-finite size");
  switch (s.type) {
    case StaticShape::Type::kBox: {
      if (s.size.minCoeff() <= 0.0) throw PhysicsError(what + ": box sizes must be positive");
      auto box = std::make_unique<btBoxShape>(toBt(Eigen::Vector3d(0.5 * s.size)));
      box->setMargin(std::min(margin, 0.25 * s.size.minCoeff()));
      body->shape = std::move(box);
      break;
    }
    case StaticShape::Type::kCylinder: {
      if (s.size.x() <= 0.0 || s.size.z() <= 0.0) {
        throw PhysicsError(what + ": cylinder radius and length must be positive");
      }
      auto cyl = std::make_unique<btCylinderShapeZ>(
          btVector3(s.size.x(), s.size.x(), 0.5 * s.size.z()));
      cyl->setMargin(std::min(margin, 0.25 * std::min(s.size.x(), s.size.z())));
      body->shape = std::move(cyl);
      break;
    }
    case StaticShape::Type::kSphere: {
      if (s.size.x() <= 0.0) throw PhysicsError(what + ": sphere radius must be positive");
      body->shape = std::make_unique<btSphereShape>(s.size.x());
      break;
    }
    case StaticShape::Type::kPlane: {
      if (!(s.size.norm() > 0.0)) throw PhysicsError(what + ": plane normal is zero");
      body->shape = std::make_unique<btStaticPlaneShape>(toBt(Eigen::Vector3d(s.size.normalized())), 0.0);
      break;
    }
    case StaticShape::Type::kMesh: {
      const auto mesh = MeshCache::global().get(s.mesh_path, s.mesh_scale);
      body->mesh_vertices.reserve(mesh->vertices.size() * 3);
      for (const auto& v : mesh->vertices) {
        body->mesh_vertices.insert(body->mesh_vertices.end(), {v.x(), v.y(), v.z()});
      }
      body->mesh_indices.assign(mesh->indices.begin(), mesh->indices.end());
      body->mesh_interface = std::make_unique<btTriangleIndexVertexArray>(
          static_cast<int>(mesh->triangleCount()), body->mesh_indices.data(), 3 * sizeof(int),
          static_cast<int>(mesh->vertices.size()), body->mesh_vertices.data(),
          3 * sizeof(btScalar));
      body->shape = std::make_unique<btBvhTriangleMeshShape>(body->mesh_interface.get(), true);
      break;
    }
  }
  body->surfaces = std::make_unique<ColliderSurfaces>();
  body->surfaces->children.push_back(toSurface(s.surface, Eigen::Matrix3d::Identity()));
  body->object = std::make_unique<btCollisionObject>();
  body->object->setCollisionShape(body->shape.get());
  body->object->setWorldTransform(toBt(s.X_WS));
  body->object->setCollisionFlags(btCollisionObject::CF_STATIC_OBJECT |
                                  btCollisionObject::CF_CUSTOM_MATERIAL_CALLBACK);
  // Static shapes stay isotropic (mu1 and mu2 still combine by min per contact): the factors
  // would multiply with the robot's, and Gazebo's ground (100 / 50) would halve a wheel's mu2.
  body->object->setFriction(s.surface.mu1);
  body->object->setRestitution(0.0);
  body->object->setUserPointer(body->surfaces.get());
  body->object->setUserIndex(-1);
  body->object->setUserIndex2(index);
  body->object->setActivationState(ISLAND_SLEEPING);  // see setForceUpdateAllAabbs above
  world->addCollisionObject(body->object.get(), btBroadphaseProxy::StaticFilter,
                            btBroadphaseProxy::AllFilter ^ btBroadphaseProxy::StaticFilter);
  return body;
}

std::unique_ptr<btCollisionShape> PhysicsWorld::Impl::makeRobotShape(
    const RobotState& r, const TreeBody& body, const CollisionGeometry& g,
    Eigen::Isometry3d* X_BS, bool* is_wheel) {
  const double margin = options.collision_margin;
  const std::string what = "robot '" + r.name + "' link '" + g.link + "'";
  *X_BS = g.X_BG;

  // Wheels: a round mesh (or a cylinder along the axis) on a continuous joint's child link.
  const bool wheel_joint = body.parent >= 0 && body.joint_type == TreeJointType::kContinuous;
  WheelFit fit;
  std::vector<Eigen::Vector3d> verts_B;
  if (g.type == GeometryType::kMesh) {
    const auto mesh = MeshCache::global().get(g.mesh_path, g.mesh_scale);
    verts_B.reserve(mesh->vertices.size());
    for (const auto& v : mesh->vertices) verts_B.push_back(g.X_BG * v.cast<double>());
    if (wheel_joint && options.wheel_shape != WheelShape::kMeshHull) {
      fit = fitWheel(verts_B, body.axis_B);
    }
  } else if (g.type == GeometryType::kCylinder && wheel_joint) {
    const Eigen::Vector3d cyl_axis = g.X_BG.linear().col(2);
    const Eigen::Vector3d c = g.X_BG.translation();
    const Eigen::Vector3d off = c - c.dot(body.axis_B) * body.axis_B;
    if (std::abs(std::abs(cyl_axis.dot(body.axis_B)) - 1.0) < 1e-9 && off.norm() < 1e-9) {
      fit.is_wheel = true;
      fit.radius = g.size.x();
      fit.width = g.size.z();
      fit.center = c;
      fit.roundness = 1.0;
    }
  }
  *is_wheel = fit.is_wheel && options.wheel_shape != WheelShape::kMeshHull;
  if (fit.is_wheel) {
    X_BS->linear() = rotationYTo(body.axis_B);
    X_BS->translation() = fit.center;
    const double R = fit.radius, W = fit.width;
    switch (options.wheel_shape) {
      case WheelShape::kRoundedCylinder: {
        // Margin W/2 rounds the whole tread: the implicit disc has radius R - W/2, height 0.
        const double m = std::min(0.5 * W, 0.5 * R);
        auto s = std::make_unique<btCylinderShape>(btVector3(R, 0.5 * W, R));
        s->setMargin(m);
        return s;
      }
      case WheelShape::kCylinder: {
        auto s = std::make_unique<btCylinderShape>(btVector3(R, 0.5 * W, R));
        s->setMargin(std::min(margin, 0.25 * std::min(R, 0.5 * W)));
        return s;
      }
      case WheelShape::kSphere:
        return std::make_unique<btSphereShape>(R);
      case WheelShape::kMeshHull:
        break;
    }
  }

  switch (g.type) {
    case GeometryType::kBox: {
      if (g.size.minCoeff() <= 0.0) throw PhysicsError(what + ": box sizes must be positive");
      auto s = std::make_unique<btBoxShape>(toBt(Eigen::Vector3d(0.5 * g.size)));
      s->setMargin(std::min(margin, 0.25 * g.size.minCoeff()));
      return s;
    }
    case GeometryType::kCylinder: {
      if (g.size.x() <= 0.0 || g.size.z() <= 0.0) {
        throw PhysicsError(what + ": cylinder radius and length must be positive");
      }
      auto s = std::make_unique<btCylinderShapeZ>(
          btVector3(g.size.x(), g.size.x(), 0.5 * g.size.z()));
      s->setMargin(std::min(margin, 0.25 * std::min(g.size.x(), g.size.z())));
      return s;
    }
    case GeometryType::kSphere:
      if (g.size.x() <= 0.0) throw PhysicsError(what + ": sphere radius must be positive");
      return std::make_unique<btSphereShape>(g.size.x());
    case GeometryType::kMesh: {
      // Hull in the body frame (vertices already there): the child transform is identity.
      X_BS->setIdentity();
      std::vector<btVector3> pts;
      pts.reserve(verts_B.size());
      for (const auto& v : verts_B) pts.push_back(toBt(v));
      return makeHull(pts, margin);
    }
  }
  throw PhysicsError(what + ": unsupported geometry");
}

void PhysicsWorld::Impl::buildRobot(RobotState* r, const RobotModel& model) {
  if (!model.urdf) throw PhysicsError("robot '" + r->name + "': model has no URDF");
  r->tree = buildRigidTree(*model.urdf, model.mesh_paths);
  const RigidTree& tree = r->tree;
  const int nb = static_cast<int>(tree.bodies.size());
  const int nlinks = nb - 1;

  // Principal COM frames.
  std::vector<Eigen::Vector3d> moments(nb);
  r->X_BC.assign(nb, Eigen::Isometry3d::Identity());
  for (int b = 0; b < nb; ++b) {
    const MassProperties& m = tree.bodies[b].mass;
    if (m.mass > 0.0) {
      const PrincipalInertia p = principalInertia(m.inertia);
      moments[b] = p.moments;
      r->X_BC[b].linear() = p.R;
      r->X_BC[b].translation() = m.com;
    } else {
      moments[b].setZero();
    }
  }

  const TreeBody& root = tree.bodies[0];
  r->mb = std::make_unique<btMultiBody>(nlinks, tree.fixed_base ? 0.0 : root.mass.mass,
                                        toBt(moments[0]), tree.fixed_base, false);
  r->mb->setBaseName(nullptr);
  for (int b = 1; b < nb; ++b) {
    const TreeBody& body = tree.bodies[b];
    const int link = b - 1, parent_link = body.parent - 1;
    const Eigen::Isometry3d X_PcB = r->X_BC[body.parent].inverse() * body.X_PB;  // joint in Pc
    const Eigen::Isometry3d X_CcB = r->X_BC[b].inverse();                         // joint in Cc
    const btQuaternion rot_parent_to_this =
        toBtQuat(X_CcB.linear() * X_PcB.linear().transpose());
    const btVector3 axis_C = toBt(Eigen::Vector3d(X_CcB.linear() * body.axis_B));
    const btVector3 parent_com_to_pivot = toBt(Eigen::Vector3d(X_PcB.translation()));
    const btVector3 pivot_to_com = toBt(Eigen::Vector3d(-X_CcB.translation()));
    if (body.joint_type == TreeJointType::kPrismatic) {
      r->mb->setupPrismatic(link, body.mass.mass, toBt(moments[b]), parent_link,
                            rot_parent_to_this, axis_C, parent_com_to_pivot, pivot_to_com, true);
    } else {
      r->mb->setupRevolute(link, body.mass.mass, toBt(moments[b]), parent_link,
                           rot_parent_to_this, axis_C, parent_com_to_pivot, pivot_to_com, true);
    }
  }
  r->mb->finalizeMultiDof();
  // Gazebo/ODE have no velocity damping and no speed cap.
  r->mb->setLinearDamping(0.0);
  r->mb->setAngularDamping(0.0);
  r->mb->setMaxCoordinateVelocity(1e4);
  r->mb->setHasSelfCollision(false);
  r->mb->setCanSleep(false);
  r->mb->setUseGyroTerm(true);
  world->addMultiBody(r->mb.get());

  // Colliders, one per body with collisions: a compound in the COM frame.
  r->colliders.resize(nb);
  for (int b = 0; b < nb; ++b) {
    const TreeBody& body = tree.bodies[b];
    if (body.collisions.empty()) {
      // Bullet files a joint motor or limit under the island of its link's collider and skips
      // it when there is none: a body without geometry gets a 1 mm sphere that collides with
      // nothing (mask 0).
      auto sphere = std::make_unique<btSphereShape>(1e-3);
      auto surfaces = std::make_unique<ColliderSurfaces>();
      surfaces->children.emplace_back();
      auto col = std::make_unique<btMultiBodyLinkCollider>(r->mb.get(), b - 1);
      col->setCollisionShape(sphere.get());
      col->setActivationState(DISABLE_DEACTIVATION);
      col->setUserPointer(surfaces.get());
      col->setUserIndex(r->id);
      col->setUserIndex2(b);
      world->addCollisionObject(col.get(), btBroadphaseProxy::DefaultFilter, 0);
      if (b == 0) {
        r->mb->setBaseCollider(col.get());
      } else {
        r->mb->getLink(b - 1).m_collider = col.get();
      }
      r->shapes.push_back(std::move(sphere));
      r->surfaces.push_back(std::move(surfaces));
      r->colliders[b] = std::move(col);
      continue;
    }
    auto compound = std::make_unique<btCompoundShape>(false, static_cast<int>(body.collisions.size()));
    auto surfaces = std::make_unique<ColliderSurfaces>();
    const Eigen::Isometry3d X_CB = r->X_BC[b].inverse();
    bool all_wheels = true;
    for (const CollisionGeometry& g : body.collisions) {
      Eigen::Isometry3d X_BS;
      bool is_wheel = false;
      std::unique_ptr<btCollisionShape> shape = makeRobotShape(*r, body, g, &X_BS, &is_wheel);
      all_wheels = all_wheels && is_wheel;
      compound->addChildShape(toBt(Eigen::Isometry3d(X_CB * X_BS)), shape.get());
      const Eigen::Matrix3d R_CL = X_CB.linear() * body.X_BL.at(g.link).linear();
      surfaces->children.push_back(toSurface(surfaceOfLink(model, g.link), R_CL));
      setRecovery(model, g.link, options, &surfaces->children.back());
      r->shapes.push_back(std::move(shape));
    }
    surfaces->robot = true;
    auto col = std::make_unique<btMultiBodyLinkCollider>(r->mb.get(), b - 1);
    col->setCollisionShape(compound.get());
    setAnisotropy(col.get(), *surfaces);
    col->setCollisionFlags(col->getCollisionFlags() | btCollisionObject::CF_CUSTOM_MATERIAL_CALLBACK);
    col->setActivationState(DISABLE_DEACTIVATION);
    col->setFriction(surfaces->children[0].mu1);
    col->setRestitution(0.0);
    col->setRollingFriction(0.0);
    col->setSpinningFriction(0.0);
    col->setUserPointer(surfaces.get());
    col->setUserIndex(r->id);
    col->setUserIndex2(b);
    if (all_wheels) {
      // A rolling wheel's manifold keeps up to 3 stale points behind the contact (rising off
      // the ground, 0.01-1 mm up) which Bullet would solve as speculative contacts: 4x the rows
      // and a little drag. The narrowphase finds the true contact afresh every step, so only
      // touching points are solved for wheels.
      col->setContactProcessingThreshold(0.0);
      surfaces->wheel = true;
    }
    world->addCollisionObject(col.get(), btBroadphaseProxy::DefaultFilter,
                              btBroadphaseProxy::AllFilter);
    if (b == 0) {
      r->mb->setBaseCollider(col.get());
    } else {
      r->mb->getLink(b - 1).m_collider = col.get();
    }
    r->shapes.push_back(std::move(compound));
    r->surfaces.push_back(std::move(surfaces));
    r->colliders[b] = std::move(col);
  }

  // Tyres: stiffness as given, damping from the damping ratio of one wheel carrying its share
  // of the robot's mass on that spring, kd = 2 zeta sqrt(k m / wheels).
  int wheels = 0;
  double mass = 0.0;
  for (int b = 0; b < nb; ++b) {
    mass += tree.bodies[b].mass.mass;
    if (r->surfaces[b]->wheel) ++wheels;
  }
  for (auto& sf : r->surfaces) {
    if (!sf->wheel || !(options.tyre_stiffness > 0.0)) continue;
    sf->tyre_stiffness = options.tyre_stiffness;
    sf->tyre_damping =
        2.0 * options.tyre_damping_ratio * std::sqrt(options.tyre_stiffness * mass / wheels);
  }

  // Joints: info, limits, motors (added to the world when first used).
  for (int b = 1; b < nb; ++b) {
    const TreeBody& body = tree.bodies[b];
    JointInfo j;
    j.name = body.joint;
    j.type = body.joint_type == TreeJointType::kRevolute
                 ? JointType::kRevolute
                 : (body.joint_type == TreeJointType::kPrismatic ? JointType::kPrismatic
                                                                 : JointType::kContinuous);
    j.parent_link = tree.bodies[body.parent].link;
    j.child_link = body.link;
    j.axis = body.axis_B;
    j.has_position_limits = body.has_position_limits;
    j.lower = body.lower;
    j.upper = body.upper;
    j.effort_limit = body.effort_limit;
    j.velocity_limit = body.velocity_limit;
    j.damping = body.damping;
    j.friction = body.friction;
    j.motor_effort = body.effort_limit > 0.0 ? body.effort_limit : options.default_motor_effort;
    r->joint_index[j.name] = static_cast<int>(r->joints.size());
    r->joints.push_back(j);
    if (j.has_position_limits) {
      auto lim = std::make_unique<btMultiBodyJointLimitConstraint>(r->mb.get(), b - 1, j.lower, j.upper);
      lim->finalizeMultiDof();
      r->limits.push_back(std::move(lim));
      r->limit_joint.push_back(static_cast<int>(r->joints.size()) - 1);
      r->limit_in_world.push_back(false);
    }
    r->motors.push_back(std::make_unique<btMultiBodyJointMotor>(r->mb.get(), b - 1, 0.0, 0.0));
    r->motors.back()->finalizeMultiDof();  // allocates the row data read by jointEffort()
    r->motor_in_world.push_back(false);
  }
  r->commands.assign(r->joints.size(), RobotState::Command());
  r->applied_effort.assign(r->joints.size(), 0.0);
  for (const TreeBody& body : tree.bodies) {
    for (const auto& l : body.merged_links) r->link_names.push_back(l);
  }
  r->scratch_q.resize(nb);
  r->scratch_p.resize(nb);
}

btTransform RobotState::comFrame(int b) const {
  if (b == 0) return mb->getBaseWorldTransform();
  mb->forwardKinematics(scratch_q, scratch_p);
  const btQuaternion& q = scratch_q[b];
  return btTransform(q.inverse(), scratch_p[b]);
}

void RobotState::syncColliders() {
  mb->forwardKinematics(scratch_q, scratch_p);
  mb->updateCollisionObjectWorldTransforms(scratch_q, scratch_p);
  for (auto& c : colliders) {
    if (c) world->world->updateSingleAabb(c.get());
  }
}

void PhysicsWorld::Impl::applyCommands(RobotState* r) {
  const double dt = options.dt;
  // A limit constraint costs two solver rows every step, also far from the limit: it joins the
  // solve only while the joint is within 0.05 rad (or two steps of travel) of either end, so it
  // cannot be crossed unseen.
  for (std::size_t k = 0; k < r->limits.size(); ++k) {
    const JointInfo& j = r->joints[r->limit_joint[k]];
    const int link = r->limit_joint[k];
    const double q = r->mb->getJointPos(link);
    const double margin = 0.05 + 2.0 * std::abs(r->mb->getJointVel(link)) * dt;
    const bool near = q - j.lower < margin || j.upper - q < margin;
    if (near != r->limit_in_world[k]) {
      if (near) {
        world->addMultiBodyConstraint(r->limits[k].get());
      } else {
        world->removeMultiBodyConstraint(r->limits[k].get());
      }
      r->limit_in_world[k] = near;
    }
  }
  for (std::size_t i = 0; i < r->joints.size(); ++i) {
    const JointInfo& j = r->joints[i];
    const RobotState::Command& c = r->commands[i];
    const int link = static_cast<int>(i);
    double tau = c.mode == RobotState::Mode::kEffort ? c.effort : 0.0;
    if (j.damping > 0.0) tau -= j.damping * r->mb->getJointVel(link);
    if (tau != 0.0) r->mb->addJointTorque(link, tau);

    btMultiBodyJointMotor* motor = r->motors[i].get();
    double target = 0.0, max_impulse = 0.0;
    if (c.mode == RobotState::Mode::kVelocity) {
      target = c.velocity;
      max_impulse = c.max_effort * dt;
    } else if (j.friction > 0.0) {
      max_impulse = j.friction * dt;
    }
    if (max_impulse > 0.0 && !r->motor_in_world[i]) {
      world->addMultiBodyConstraint(motor);
      r->motor_in_world[i] = true;
    }
    if (r->motor_in_world[i]) {
      motor->setVelocityTarget(target, 1.0);
      motor->setMaxAppliedImpulse(max_impulse);
    }
  }
}

// ---------------------------------------------------------------------------------------------
// PhysicsWorld

PhysicsWorld::PhysicsWorld(const PhysicsOptions& options) : impl_(std::make_unique<Impl>(options)) {}
PhysicsWorld::~PhysicsWorld() = default;

RobotId PhysicsWorld::addRobot(const RobotModel& model, const Eigen::Isometry3d& X_WB_spawn,
                               const std::string& name) {
  if (robotId(name) >= 0) throw PhysicsError("robot '" + name + "' already exists");
  if (!X_WB_spawn.matrix().allFinite()) {
    throw PhysicsError("robot '" + name + "': non-finite spawn pose");
  }
  auto r = std::make_unique<RobotState>();
  r->world = impl_.get();
  r->id = static_cast<RobotId>(impl_->robots.size());
  r->name = name;
  r->spawn = X_WB_spawn;
  r->spawn.linear() = Eigen::Quaterniond(X_WB_spawn.rotation()).normalized().toRotationMatrix();
  RobotState* rp = r.get();
  impl_->robots.push_back(std::move(r));
  try {
    impl_->buildRobot(rp, model);
  } catch (...) {
    // Undo what was added to the Bullet world, then rethrow.
    auto& w = impl_->world;
    for (std::size_t j = 0; j < rp->motors.size(); ++j) {
      if (rp->motor_in_world[j]) w->removeMultiBodyConstraint(rp->motors[j].get());
    }
    for (std::size_t k = 0; k < rp->limits.size(); ++k) {
      if (rp->limit_in_world[k]) w->removeMultiBodyConstraint(rp->limits[k].get());
    }
    for (auto& c : rp->colliders) {
      if (c) w->removeCollisionObject(c.get());
    }
    if (rp->mb) w->removeMultiBody(rp->mb.get());
    impl_->robots.pop_back();
    throw;
  }
  rp->handle.resetToSpawn();
  return rp->id;
}

int PhysicsWorld::addStaticShape(const StaticShape& shape) {
  const int index = static_cast<int>(impl_->statics.size());
  impl_->statics.push_back(impl_->makeStatic(shape, index));
  return index;
}

void PhysicsWorld::step() {
  for (auto& r : impl_->robots) impl_->applyCommands(r.get());
  // maxSubSteps = 0: exactly one internal step of dt (no accumulator, no interpolation).
  impl_->world->stepSimulation(impl_->options.dt, 0, impl_->options.dt);
  ++impl_->steps;
  const double inv_dt = 1.0 / impl_->options.dt;
  for (auto& r : impl_->robots) {
    for (std::size_t i = 0; i < r->joints.size(); ++i) {
      const RobotState::Command& c = r->commands[i];
      if (c.mode == RobotState::Mode::kEffort) {
        r->applied_effort[i] = c.effort;
      } else if (c.mode == RobotState::Mode::kVelocity) {
        btMultiBodyJointMotor* m = r->motors[i].get();
        r->applied_effort[i] = m->getNumRows() > 0 ? m->getAppliedImpulse(0) * inv_dt : 0.0;
      } else {
        r->applied_effort[i] = 0.0;
      }
    }
  }
}

double PhysicsWorld::dt() const { return impl_->options.dt; }
double PhysicsWorld::time() const { return static_cast<double>(impl_->steps) * impl_->options.dt; }
std::uint64_t PhysicsWorld::stepCount() const { return impl_->steps; }
void PhysicsWorld::resetTime() { impl_->steps = 0; }
int PhysicsWorld::robotCount() const { return static_cast<int>(impl_->robots.size()); }

PhysicsRobot& PhysicsWorld::robot(RobotId id) {
  if (id < 0 || id >= robotCount()) throw PhysicsError("no robot with id " + std::to_string(id));
  return impl_->robots[id]->handle;
}
const PhysicsRobot& PhysicsWorld::robot(RobotId id) const {
  if (id < 0 || id >= robotCount()) throw PhysicsError("no robot with id " + std::to_string(id));
  return impl_->robots[id]->handle;
}
RobotId PhysicsWorld::robotId(const std::string& name) const {
  for (const auto& r : impl_->robots) {
    if (r->name == name) return r->id;
  }
  return -1;
}
const PhysicsOptions& PhysicsWorld::options() const { return impl_->options; }
btMultiBodyDynamicsWorld* PhysicsWorld::bulletWorld() { return impl_->world.get(); }

// ---------------------------------------------------------------------------------------------
// PhysicsRobot

const std::string& PhysicsRobot::name() const { return s_->name; }
const RigidTree& PhysicsRobot::tree() const { return s_->tree; }
const std::vector<JointInfo>& PhysicsRobot::joints() const { return s_->joints; }

int PhysicsRobot::jointIndex(const std::string& joint_name) const {
  auto it = s_->joint_index.find(joint_name);
  return it == s_->joint_index.end() ? -1 : it->second;
}

namespace {
void checkJoint(const RobotState* s, int i) {
  if (i < 0 || i >= static_cast<int>(s->joints.size())) {
    throw PhysicsError("robot '" + s->name + "': no joint index " + std::to_string(i));
  }
}
}  // namespace

double PhysicsRobot::jointPosition(int i) const {
  checkJoint(s_, i);
  return s_->mb->getJointPos(i);
}
double PhysicsRobot::jointVelocity(int i) const {
  checkJoint(s_, i);
  return s_->mb->getJointVel(i);
}
double PhysicsRobot::jointEffort(int i) const {
  checkJoint(s_, i);
  return s_->applied_effort[i];
}

void PhysicsRobot::setJointEffort(int i, double tau) {
  checkJoint(s_, i);
  assert(std::isfinite(tau) && "setJointEffort: non-finite effort");
  if (!std::isfinite(tau)) {
    ++s_->rejected;
    return;
  }
  const double lim = s_->joints[i].effort_limit;
  if (lim > 0.0) tau = std::max(-lim, std::min(lim, tau));
  auto& c = s_->commands[i];
  c.mode = RobotState::Mode::kEffort;
  c.effort = tau;
}

void PhysicsRobot::setJointVelocityTarget(int i, double omega, double max_effort) {
  checkJoint(s_, i);
  assert(std::isfinite(omega) && std::isfinite(max_effort) &&
         "setJointVelocityTarget: non-finite command");
  if (!std::isfinite(omega) || !std::isfinite(max_effort)) {
    ++s_->rejected;
    return;
  }
  auto& c = s_->commands[i];
  c.mode = RobotState::Mode::kVelocity;
  c.velocity = omega;
  c.max_effort = max_effort < 0.0 ? s_->joints[i].motor_effort : max_effort;
}

void PhysicsRobot::clearJointCommand(int i) {
  checkJoint(s_, i);
  s_->commands[i] = RobotState::Command();
}

void PhysicsRobot::setJointState(int i, double position, double velocity) {
  checkJoint(s_, i);
  if (!std::isfinite(position) || !std::isfinite(velocity)) {
    ++s_->rejected;
    return;
  }
  s_->mb->setJointPos(i, position);
  s_->mb->setJointVel(i, velocity);
  s_->syncColliders();
}

std::uint64_t PhysicsRobot::rejectedCommands() const { return s_->rejected; }

Eigen::Isometry3d PhysicsRobot::basePose() const {
  return toEigen(s_->mb->getBaseWorldTransform()) * s_->X_BC[0].inverse();
}

Twist PhysicsRobot::baseTwist() const {
  Twist t;
  t.angular = toEigen(s_->mb->getBaseOmega());
  const Eigen::Vector3d v_com = toEigen(s_->mb->getBaseVel());
  const btTransform X_WC = s_->mb->getBaseWorldTransform();
  const Eigen::Vector3d p_com = toEigen(X_WC.getOrigin());
  const Eigen::Vector3d p_origin = basePose().translation();
  t.linear = v_com + t.angular.cross(p_origin - p_com);
  return t;
}

void PhysicsRobot::setBasePose(const Eigen::Isometry3d& X_WB) {
  if (!X_WB.matrix().allFinite()) {
    ++s_->rejected;
    return;
  }
  Eigen::Isometry3d X = X_WB;
  X.linear() = Eigen::Quaterniond(X_WB.rotation()).normalized().toRotationMatrix();
  s_->mb->setBaseWorldTransform(toBt(Eigen::Isometry3d(X * s_->X_BC[0])));
  s_->syncColliders();
}

void PhysicsRobot::setBaseTwist(const Twist& twist) {
  if (!twist.linear.allFinite() || !twist.angular.allFinite()) {
    ++s_->rejected;
    return;
  }
  const Eigen::Vector3d p_com = toEigen(s_->mb->getBaseWorldTransform().getOrigin());
  const Eigen::Vector3d p_origin = basePose().translation();
  s_->mb->setBaseVel(toBt(Eigen::Vector3d(twist.linear + twist.angular.cross(p_com - p_origin))));
  s_->mb->setBaseOmega(toBt(twist.angular));
}

void PhysicsRobot::resetToSpawn() {
  for (std::size_t i = 0; i < s_->joints.size(); ++i) {
    s_->mb->setJointPos(static_cast<int>(i), 0.0);
    s_->mb->setJointVel(static_cast<int>(i), 0.0);
    s_->commands[i] = RobotState::Command();
    s_->applied_effort[i] = 0.0;
  }
  s_->mb->setBaseWorldTransform(toBt(Eigen::Isometry3d(s_->spawn * s_->X_BC[0])));
  s_->mb->setBaseVel(btVector3(0, 0, 0));
  s_->mb->setBaseOmega(btVector3(0, 0, 0));
  s_->mb->clearForcesAndTorques();
  s_->mb->clearConstraintForces();
  s_->syncColliders();
  // Forget contacts (and their warm-start impulses) of the old pose.
  auto* w = s_->world->world.get();
  for (auto& c : s_->colliders) {
    if (c && c->getBroadphaseHandle()) {
      w->getBroadphase()->getOverlappingPairCache()->cleanProxyFromPairs(c->getBroadphaseHandle(),
                                                                         w->getDispatcher());
    }
  }
}

const Eigen::Isometry3d& PhysicsRobot::spawnPose() const { return s_->spawn; }
const std::vector<std::string>& PhysicsRobot::linkNames() const { return s_->link_names; }

Eigen::Isometry3d PhysicsRobot::linkPose(const std::string& link) const {
  auto it = s_->tree.links.find(link);
  if (it == s_->tree.links.end()) {
    throw PhysicsError("robot '" + s_->name + "': unknown link '" + link + "'");
  }
  const int b = it->second.first;
  return toEigen(s_->comFrame(b)) * s_->X_BC[b].inverse() * it->second.second;
}

int PhysicsRobot::contactCount(const std::string& link, double max_distance) const {
  const int b = s_->bodyOf(link);
  const btCollisionObject* col = s_->colliders[b].get();
  if (col == nullptr) return 0;
  btDispatcher* d = s_->world->world->getDispatcher();
  int count = 0;
  for (int m = 0; m < d->getNumManifolds(); ++m) {
    const btPersistentManifold* pm = d->getManifoldByIndexInternal(m);
    if (pm->getBody0() != col && pm->getBody1() != col) continue;
    for (int p = 0; p < pm->getNumContacts(); ++p) {
      if (pm->getContactPoint(p).getDistance() <= max_distance) ++count;
    }
  }
  return count;
}

double PhysicsRobot::contactNormalForce(const std::string& link) const {
  const int b = s_->bodyOf(link);
  const btCollisionObject* col = s_->colliders[b].get();
  if (col == nullptr) return 0.0;
  btDispatcher* d = s_->world->world->getDispatcher();
  double impulse = 0.0;
  for (int m = 0; m < d->getNumManifolds(); ++m) {
    const btPersistentManifold* pm = d->getManifoldByIndexInternal(m);
    if (pm->getBody0() != col && pm->getBody1() != col) continue;
    for (int p = 0; p < pm->getNumContacts(); ++p) {
      const btManifoldPoint& cp = pm->getContactPoint(p);
      // Points beyond the processing threshold are not solved and keep stale impulses.
      if (cp.getDistance() <= pm->getContactProcessingThreshold()) impulse += cp.getAppliedImpulse();
    }
  }
  return impulse / s_->world->options.dt;
}

double PhysicsRobot::kineticEnergy() const {
  const btMultiBody& mb = *s_->mb;
  const int n = mb.getNumLinks();
  btAlignedObjectArray<btVector3> omega, vel;
  omega.resize(n + 1);
  vel.resize(n + 1);
  mb.compTreeLinkVelocities(&omega[0], &vel[0]);
  auto body = [&](double m, const btVector3& I, const btVector3& w, const btVector3& v) {
    return 0.5 * m * v.length2() + 0.5 * (I.x() * w.x() * w.x() + I.y() * w.y() * w.y() +
                                          I.z() * w.z() * w.z());
  };
  double e = body(mb.getBaseMass(), mb.getBaseInertia(), omega[0], vel[0]);
  for (int i = 0; i < n; ++i) e += body(mb.getLinkMass(i), mb.getLinkInertia(i), omega[i + 1], vel[i + 1]);
  return e;
}

double PhysicsRobot::potentialEnergy() const {
  const Eigen::Vector3d g = s_->world->options.gravity;
  double e = 0.0;
  for (std::size_t b = 0; b < s_->tree.bodies.size(); ++b) {
    const Eigen::Vector3d p = toEigen(s_->comFrame(static_cast<int>(b)).getOrigin());
    e -= s_->tree.bodies[b].mass.mass * g.dot(p);
  }
  return e;
}

double PhysicsRobot::totalMass() const {
  double m = 0.0;
  for (const auto& b : s_->tree.bodies) m += b.mass.mass;
  return m;
}

const btCollisionObject* PhysicsRobot::collisionObject(const std::string& link) const {
  const int b = s_->bodyOf(link);
  return s_->tree.bodies[b].collisions.empty() ? nullptr : s_->colliders[b].get();
}

}  // namespace tianracer_sim
