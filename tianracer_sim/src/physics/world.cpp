// PhysicsWorld: the Bullet world, static shapes, stepping and the world API.
#include "tianracer_sim/physics/world.h"

#include <cmath>
#include <sstream>
#include <string>

#include "world_impl.h"

namespace tianracer_sim {

namespace {

/// A pair algorithm of ours with a manifold of its own (as Bullet's GImpact algorithm has): the
/// construction, the manifold's lifetime and the create function, shared by the mesh pairs below.
/// `swapped_`: the mesh is the second object of the pair.
template <class Derived>
class OwnManifoldAlgorithm : public btActivatingCollisionAlgorithm {
 public:
  OwnManifoldAlgorithm(const btCollisionAlgorithmConstructionInfo& ci, const btCollisionObjectWrapper* a,
                       const btCollisionObjectWrapper* b, bool swapped)
      : btActivatingCollisionAlgorithm(ci, a, b), swapped_(swapped) {
    manifold_ = m_dispatcher->getNewManifold(a->getCollisionObject(), b->getCollisionObject());
  }
  ~OwnManifoldAlgorithm() override {
    if (manifold_) m_dispatcher->releaseManifold(manifold_);
  }
  btScalar calculateTimeOfImpact(btCollisionObject*, btCollisionObject*, const btDispatcherInfo&,
                                 btManifoldResult*) override {
    return 1;
  }
  void getAllContactManifolds(btManifoldArray& arr) override {
    if (manifold_) arr.push_back(manifold_);
  }

  struct CreateFunc : public btCollisionAlgorithmCreateFunc {
    btCollisionAlgorithm* CreateCollisionAlgorithm(btCollisionAlgorithmConstructionInfo& ci,
                                                   const btCollisionObjectWrapper* a,
                                                   const btCollisionObjectWrapper* b) override {
      void* mem = ci.m_dispatcher1->allocateCollisionAlgorithm(sizeof(Derived));
      return new (mem) Derived(ci, a, b, m_swapped);
    }
  };

 protected:
  btPersistentManifold* manifold_ = nullptr;
  bool swapped_;
};

/// A movable concave mesh (btGImpactMeshShape) against a plane, as ODE's dCollideTrimeshPlane
/// (Gazebo 11's deps/opende/src/collision_trimesh_plane.cpp) does it: a contact for every mesh
/// vertex below the plane. Bullet's gimpacttrimeshpart_vs_plane_collision does the same per
/// vertex, but first drops the pair unless the mesh's AABB straddles the plane within 1e-6 m
/// (btAABB::plane_classify): a flat plate (an AABB of zero thickness, no margin) never got a
/// contact and fell through the ground plane (issue 40; test_sim_movable_plate).
class MeshPlaneAlgorithm : public OwnManifoldAlgorithm<MeshPlaneAlgorithm> {
 public:
  using OwnManifoldAlgorithm::OwnManifoldAlgorithm;

  void processCollision(const btCollisionObjectWrapper* a, const btCollisionObjectWrapper* b,
                        const btDispatcherInfo&, btManifoldResult* out) override {
    const btCollisionObjectWrapper* mesh_w = swapped_ ? b : a;
    const btCollisionObjectWrapper* plane_w = swapped_ ? a : b;
    const auto* mesh = static_cast<const btGImpactMeshShape*>(mesh_w->getCollisionShape());
    const auto* plane = static_cast<const btStaticPlaneShape*>(plane_w->getCollisionShape());
    const btTransform& X_WM = mesh_w->getWorldTransform();
    const btTransform& X_WP = plane_w->getWorldTransform();
    const btVector3 n = X_WP.getBasis() * plane->getPlaneNormal();
    const btScalar d = plane->getPlaneConstant() + n.dot(X_WP.getOrigin());
    const btScalar margin = mesh->getMargin() + plane->getMargin();
    out->setPersistentManifold(manifold_);
    for (int p = 0; p < mesh->getMeshPartCount(); ++p) {
      const btGImpactMeshShapePart* part = mesh->getMeshPart(p);
      part->lockChildShapes();
      btVector3 v;
      for (int i = 0; i < part->getVertexCount(); ++i) {
        part->getVertex(i, v);
        const btVector3 v_W = X_WM(v);
        const btScalar dist = n.dot(v_W) - d - margin;
        if (dist >= 0) continue;
        // btManifoldResult wants the normal on its second body and the point on it.
        if (!swapped_) out->addContactPoint(n, v_W - n * dist, dist);
        else out->addContactPoint(-n, v_W, dist);
      }
      part->unlockChildShapes();
    }
    out->refreshContactPoints();
  }
};

MeshPlaneAlgorithm::CreateFunc g_mesh_plane, g_plane_mesh;

/// A movable concave mesh (btGImpactMeshShape) against a static one (btBvhTriangleMeshShape),
/// triangle against triangle as ODE collides two trimeshes (Gazebo 11's
/// deps/opende/src/collision_trimesh_trimesh_new.cpp, FindTriangleTriangleCollision): each
/// triangle clipped by the other's edge planes, the deepest clipped points against the other's
/// plane, and of the two directions the one of least depth. GImpact's own routine for two
/// GImpact meshes does the same (btPrimitiveTriangle::find_triangle_collision_clip_method); we
/// call its parts and choose the normal's sign ourselves, so that it always points from the
/// static mesh to the movable one's side. Like ODE's, the test is one-sided: behind a triangle is
/// inside its mesh. Bullet's GImpact-vs-concave path culled a flat plate on a flat static mesh by
/// their AABBs of zero thickness, and the plate fell through (issue 40); the pairs are found here
/// with AABBs padded by kMeshPairPad (MovableMeshShape pads its own the same).
class MeshTriMeshAlgorithm : public OwnManifoldAlgorithm<MeshTriMeshAlgorithm> {
 public:
  using OwnManifoldAlgorithm::OwnManifoldAlgorithm;

  void processCollision(const btCollisionObjectWrapper* a, const btCollisionObjectWrapper* b,
                        const btDispatcherInfo&, btManifoldResult* out) override {
    const btCollisionObjectWrapper* mesh_w = swapped_ ? b : a;
    const btCollisionObjectWrapper* fixed_w = swapped_ ? a : b;
    const auto* mesh = static_cast<const btGImpactMeshShape*>(mesh_w->getCollisionShape());
    const auto* fixed = static_cast<const btConcaveShape*>(fixed_w->getCollisionShape());
    out->setPersistentManifold(manifold_);
    TrianglePairs pairs(this, mesh_w->getWorldTransform(), fixed_w->getWorldTransform(), out);
    const btTransform X_FM = fixed_w->getWorldTransform().inverse() * mesh_w->getWorldTransform();
    for (int p = 0; p < mesh->getMeshPartCount(); ++p) {
      pairs.part = mesh->getMeshPart(p);
      pairs.part->lockChildShapes();
      btAABB box = pairs.part->getBoxSet()->getGlobalBox();
      box.appy_transform(X_FM);
      box.increment_margin(kMeshPairPad);
      fixed->processAllTriangles(&pairs, box.m_min, box.m_max);
      pairs.part->unlockChildShapes();
    }
    out->refreshContactPoints();
  }

 private:
  /// Called by the static mesh for each of its triangles near a part of the movable mesh.
  struct TrianglePairs : public btTriangleCallback {
    TrianglePairs(const MeshTriMeshAlgorithm* algo, const btTransform& X_WM, const btTransform& X_WF,
                  btManifoldResult* out)
        : swapped(algo->swapped_), X_WM(X_WM), X_WF(X_WF), X_MW(X_WM.inverse()), out(out) {}

    void processTriangle(btVector3* v, int, int) override {
      btPrimitiveTriangle fixed;  // in the world frame
      for (int i = 0; i < 3; ++i) fixed.m_vertices[i] = X_WF(v[i]);
      if (degenerate(fixed)) return;  // no plane
      fixed.buildTriPlane();
      btAABB box(X_MW(fixed.m_vertices[0]), X_MW(fixed.m_vertices[1]), X_MW(fixed.m_vertices[2]), kMeshPairPad);
      near.resize(0);
      if (!part->getBoxSet()->boxQuery(box, near)) return;
      for (int k = 0; k < near.size(); ++k) {
        btPrimitiveTriangle moving;
        part->getPrimitiveTriangle(near[k], moving);
        moving.applyTransform(X_WM);
        if (degenerate(moving)) continue;
        moving.buildTriPlane();
        collide(fixed, moving);
      }
    }

    static bool degenerate(const btPrimitiveTriangle& t) {
      const btVector3 n = (t.m_vertices[1] - t.m_vertices[0]).cross(t.m_vertices[2] - t.m_vertices[0]);
      return !(n.length2() > SIMD_EPSILON * SIMD_EPSILON);
    }

    /// The least-depth direction of the two, as find_triangle_collision_clip_method chooses it;
    /// but two triangles that face the same way (a plate lying on a floor) have no depth along
    /// the moving one's normal (a sheet has no inside: sunk below the floor, the floor is in
    /// front of it), so they are taken in the fixed triangle's direction only, the floor's solid
    /// side behind its face.
    void collide(btPrimitiveTriangle& fixed, btPrimitiveTriangle& moving) {
      btVector3 points[MAX_TRI_CLIPPING];
      GIM_TRIANGLE_CONTACT on_fixed, on_moving;  // the moving triangle's points against the fixed plane, and back
      int n = fixed.clip_triangle(moving, points);
      if (n == 0) return;
      on_fixed.merge_points(fixed.m_plane, kMeshPairPad, points, n);
      if (on_fixed.m_point_count == 0) return;
      const bool same_facing = fixed.m_plane.dot(moving.m_plane) > 0;  // btVector3::dot: xyz only
      if (!same_facing) {
        n = moving.clip_triangle(fixed, points);
        if (n == 0) return;
        on_moving.merge_points(moving.m_plane, kMeshPairPad, points, n);
        if (on_moving.m_point_count == 0) return;
      }
      // merge_points' depth is kMeshPairPad minus the signed distance to the plane.
      if (same_facing || on_fixed.m_penetration_depth <= on_moving.m_penetration_depth) {
        // Moving points p, the fixed plane's normal n pointing from the fixed mesh to them.
        const btVector3 n_f = fixed.m_plane;
        const btScalar dist = kMeshPairPad - on_fixed.m_penetration_depth;
        if (dist >= 0) return;
        for (int i = 0; i < on_fixed.m_point_count; ++i) {
          const btVector3& p = on_fixed.m_points[i];
          // btManifoldResult wants the normal on its second body and the point on it.
          if (!swapped) out->addContactPoint(n_f, p - n_f * dist, dist);
          else out->addContactPoint(-n_f, p, dist);
        }
      } else {
        // Fixed points q, in front of the moving plane: from the fixed mesh to the moving one is -n_m.
        const btVector3 n_m = moving.m_plane;
        const btScalar dist = kMeshPairPad - on_moving.m_penetration_depth;
        if (dist >= 0) return;
        for (int i = 0; i < on_moving.m_point_count; ++i) {
          const btVector3& q = on_moving.m_points[i];
          if (!swapped) out->addContactPoint(-n_m, q, dist);
          else out->addContactPoint(n_m, q - n_m * dist, dist);
        }
      }
    }

    const bool swapped;
    const btTransform X_WM, X_WF, X_MW;
    btManifoldResult* out;
    const btGImpactMeshShapePart* part = nullptr;
    btAlignedObjectArray<int> near;
  };

};

MeshTriMeshAlgorithm::CreateFunc g_mesh_trimesh, g_trimesh_mesh;

}  // namespace

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
  if (!(options.sleep_speed >= 0.0) || !std::isfinite(options.sleep_speed) ||
      !(options.sleep_time >= 0.0) || !std::isfinite(options.sleep_time)) {
    throw PhysicsError("physics: sleep_speed and sleep_time must be finite and >= 0, got " +
                       std::to_string(options.sleep_speed) + " and " +
                       std::to_string(options.sleep_time));
  }
  config = std::make_unique<btDefaultCollisionConfiguration>();
  dispatcher = std::make_unique<btCollisionDispatcher>(config.get());
  // Concave meshes of world models (btGImpactMeshShape) against everything.
  btGImpactCollisionAlgorithm::registerAlgorithm(dispatcher.get());
  // ... except against planes: ODE's every vertex below the plane (MeshPlaneAlgorithm above).
  g_plane_mesh.m_swapped = true;
  dispatcher->registerCollisionCreateFunc(GIMPACT_SHAPE_PROXYTYPE, STATIC_PLANE_PROXYTYPE, &g_mesh_plane);
  dispatcher->registerCollisionCreateFunc(STATIC_PLANE_PROXYTYPE, GIMPACT_SHAPE_PROXYTYPE, &g_plane_mesh);
  // ... and against static meshes: ODE's triangle against triangle (MeshTriMeshAlgorithm above).
  g_trimesh_mesh.m_swapped = true;
  dispatcher->registerCollisionCreateFunc(GIMPACT_SHAPE_PROXYTYPE, TRIANGLE_MESH_SHAPE_PROXYTYPE, &g_mesh_trimesh);
  dispatcher->registerCollisionCreateFunc(TRIANGLE_MESH_SHAPE_PROXYTYPE, GIMPACT_SHAPE_PROXYTYPE, &g_trimesh_mesh);
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
  // Islands stay split (Bullet's default): with setSplitIslands(false) Bullet 3.24's
  // MultiBodyInplaceSolverIslandCallback::processIsland hands the solver 0 multibody
  // constraints, so every joint motor is dropped and the car does not move (issue 27's
  // settings table in docs/performance.md).
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
  broadphase->getOverlappingPairCache()->setOverlapFilterCallback(&model_filter);

  if (options.ground_plane) {
    StaticShape g;
    g.name = "ground_plane";
    g.shape.type = ShapeType::kPlane;
    g.shape.normal = Eigen::Vector3d::UnitZ();
    g.surface.mu1 = options.ground_mu;
    g.surface.mu2 = options.ground_mu2;
    g.surface.kp = options.ground_kp;
    g.surface.kd = options.ground_kd;
    ground = makeStatic(g, -1);
  }
}

PhysicsWorld::Impl::~Impl() {
  for (auto& r : robots)
    if (r) removeFromWorld(r.get());
  for (auto& b : free_bodies)
    if (b) removeFromWorld(b.get());
  for (auto& s : statics)
    if (s) world->removeCollisionObject(s->object.get());
  if (ground) world->removeCollisionObject(ground->object.get());
  robots.clear();
  free_bodies.clear();
  statics.clear();
  ground.reset();
  world.reset();
}

std::unique_ptr<PhysicsWorld::Impl::StaticBody> PhysicsWorld::Impl::makeStatic(
    const StaticShape& s, int index) {
  auto body = std::make_unique<StaticBody>();
  makeStaticShape(s, options.collision_margin, &body->shape);
  body->surfaces = std::make_unique<ColliderSurfaces>();
  body->surfaces->children.push_back(toSurface(s.surface, Eigen::Matrix3d::Identity(), options.contact_max_vel));
  body->surfaces->collide_bitmask = s.surface.collide_bitmask;
  body->surfaces->without_contact_bitmask = s.surface.collide_without_contact_bitmask;
  body->surfaces->without_contact = s.surface.collide_without_contact;
  body->object = std::make_unique<btCollisionObject>();
  body->object->setCollisionShape(body->shape.shape.get());
  body->object->setWorldTransform(toBt(s.X_WS));
  body->object->setCollisionFlags(btCollisionObject::CF_STATIC_OBJECT |
                                  btCollisionObject::CF_CUSTOM_MATERIAL_CALLBACK);
  // Bullet still finds its contacts (bumpers read them) but builds no constraint for them.
  if (s.surface.collide_without_contact) {
    body->object->setCollisionFlags(body->object->getCollisionFlags() |
                                    btCollisionObject::CF_NO_CONTACT_RESPONSE);
  }
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

// ---------------------------------------------------------------------------------------------
// PhysicsWorld

PhysicsWorld::PhysicsWorld(const PhysicsOptions& options) : impl_(std::make_unique<Impl>(options)) {}
PhysicsWorld::~PhysicsWorld() = default;

void PhysicsWorld::Impl::add(std::unique_ptr<RobotState> r, const SurfaceOf& surface_of,
                             std::vector<std::unique_ptr<RobotState>>* list) {
  r->world = this;
  const Eigen::Isometry3d X = r->spawn;
  r->spawn.linear() = Eigen::Quaterniond(X.rotation()).normalized().toRotationMatrix();
  RobotState* rp = r.get();
  list->push_back(std::move(r));
  try {
    buildRobot(rp, surface_of);
  } catch (...) {
    removeFromWorld(rp);
    list->pop_back();
    throw;
  }
  rp->handle.resetToSpawn();
}

RobotId PhysicsWorld::addRobot(RigidTree tree, const LinkSurfaces& surfaces,
                               const Eigen::Isometry3d& X_WB_spawn, const std::string& name) {
  if (robotId(name) >= 0) throw PhysicsError("robot '" + name + "' already exists");
  if (!X_WB_spawn.matrix().allFinite()) {
    throw PhysicsError("robot '" + name + "': non-finite spawn pose");
  }
  if (tree.bodies.empty()) throw PhysicsError("robot '" + name + "': no bodies");
  auto r = std::make_unique<RobotState>();
  r->id = static_cast<RobotId>(impl_->robots.size());
  r->user_index = r->id;
  r->name = name;
  r->tree = std::move(tree);
  r->spawn = X_WB_spawn;
  static const SurfaceParams kDefault;  // Gazebo's defaults: mu 1, kp 1e12, kd 1
  impl_->add(std::move(r),
             [&surfaces](const CollisionGeometry& g, int) -> const SurfaceParams& {
               auto it = surfaces.find(g.link);
               return it == surfaces.end() ? kDefault : it->second;
             },
             &impl_->robots);
  return static_cast<RobotId>(impl_->robots.size()) - 1;
}

int PhysicsWorld::addFreeBody(RigidTree tree, const std::vector<SurfaceParams>& surfaces,
                              const Eigen::Isometry3d& X_WM, const std::string& name) {
  const std::string what = "free body '" + name + "'";
  if (freeBodyIndex(name) >= 0) throw PhysicsError(what + " already exists");
  if (!X_WM.matrix().allFinite()) throw PhysicsError(what + ": non-finite pose");
  if (tree.bodies.empty()) throw PhysicsError(what + ": no bodies");
  for (std::size_t b = 0; b < tree.bodies.size(); ++b) {
    if (b == 0 && tree.fixed_base) continue;
    const MassProperties& m = tree.bodies[b].mass;
    const std::string body = what + " body '" + tree.bodies[b].link + "'";
    if (!(m.mass > 0.0) || !std::isfinite(m.mass)) {
      throw PhysicsError(body + ": mass must be positive, got " + std::to_string(m.mass));
    }
    if (!isPositiveDefiniteInertia(m.inertia))
      throw PhysicsError(body + ": inertia is not symmetric positive definite");
  }
  if (tree.canonical_body < 0 || tree.canonical_body >= static_cast<int>(tree.bodies.size())) {
    throw PhysicsError(what + ": canonical body " + std::to_string(tree.canonical_body) +
                       " out of range");
  }
  auto r = std::make_unique<RobotState>();
  r->id = static_cast<int>(impl_->free_bodies.size());
  r->user_index = -2 - r->id;
  r->world_model = true;
  r->name = name;
  r->tree = std::move(tree);
  r->spawn = X_WM;
  static const SurfaceParams kDefault;
  impl_->add(std::move(r),
             [&surfaces](const CollisionGeometry&, int k) -> const SurfaceParams& {
               return k < static_cast<int>(surfaces.size()) ? surfaces[k] : kDefault;
             },
             &impl_->free_bodies);
  return static_cast<int>(impl_->free_bodies.size()) - 1;
}

int PhysicsWorld::freeBodyCount() const { return static_cast<int>(impl_->free_bodies.size()); }

PhysicsRobot& PhysicsWorld::freeBody(int index) {
  return const_cast<PhysicsRobot&>(static_cast<const PhysicsWorld*>(this)->freeBody(index));
}
const PhysicsRobot& PhysicsWorld::freeBody(int index) const {
  if (!hasFreeBody(index)) {
    throw PhysicsError("no free body with index " + std::to_string(index));
  }
  return impl_->free_bodies[index]->handle;
}
bool PhysicsWorld::hasFreeBody(int index) const {
  return index >= 0 && index < freeBodyCount() && impl_->free_bodies[index];
}
int PhysicsWorld::freeBodyIndex(const std::string& name) const {
  for (const auto& b : impl_->free_bodies) {
    if (b && b->name == name) return b->id;
  }
  return -1;
}

void PhysicsWorld::Impl::wakeTouching(const btCollisionObject* o) {
  for (int m = 0; m < dispatcher->getNumManifolds(); ++m) {
    const btPersistentManifold* pm = dispatcher->getManifoldByIndexInternal(m);
    if (pm->getBody0() != o && pm->getBody1() != o) continue;
    const btCollisionObject* other = pm->getBody0() == o ? pm->getBody1() : pm->getBody0();
    const int i = -2 - other->getUserIndex();
    if (i >= 0 && i < static_cast<int>(free_bodies.size()) && free_bodies[i]) free_bodies[i]->wake();
  }
}

void PhysicsWorld::Impl::wakeTouching(const RobotState* r) {
  for (const auto& c : r->colliders)
    if (c) wakeTouching(c.get());
}

void PhysicsWorld::removeFreeBody(int index) {
  if (!hasFreeBody(index)) throw PhysicsError("no free body with index " + std::to_string(index));
  impl_->wakeTouching(impl_->free_bodies[index].get());  // what rested on it falls
  impl_->removeFromWorld(impl_->free_bodies[index].get());
  impl_->free_bodies[index].reset();
}

int PhysicsWorld::addStaticShape(const StaticShape& shape) {
  const int index = static_cast<int>(impl_->statics.size());
  impl_->statics.push_back(impl_->makeStatic(shape, index));
  return index;
}

void PhysicsWorld::removeStaticShape(int index) {
  if (index < 0 || index >= static_cast<int>(impl_->statics.size()) || !impl_->statics[index]) {
    throw PhysicsError("no static shape with index " + std::to_string(index));
  }
  impl_->wakeTouching(impl_->statics[index]->object.get());  // what rested on it falls
  impl_->world->removeCollisionObject(impl_->statics[index]->object.get());
  impl_->statics[index].reset();
}

void PhysicsWorld::setStaticShapePose(int index, const Eigen::Isometry3d& X_WS) {
  if (index < 0 || index >= static_cast<int>(impl_->statics.size()) || !impl_->statics[index]) {
    throw PhysicsError("no static shape with index " + std::to_string(index));
  }
  if (!X_WS.matrix().allFinite()) return;
  btCollisionObject* o = impl_->statics[index]->object.get();
  if (!o->isKinematicObject()) {
    // A moving static: Bullet's kinematic object (infinite mass, never asleep), whose contacts
    // wake what it meets (btSimulationIslandManager::buildIslands) where a sleeping static's
    // would be skipped.
    o->setCollisionFlags((o->getCollisionFlags() & ~btCollisionObject::CF_STATIC_OBJECT) |
                         btCollisionObject::CF_KINEMATIC_OBJECT);
    o->forceActivationState(DISABLE_DEACTIVATION);
  }
  impl_->wakeTouching(o);  // what rested on it where it was
  o->setWorldTransform(toBt(X_WS));
  impl_->world->updateSingleAabb(o);  // static AABBs are not recomputed each step
  impl_->wakeTouching(o);
}

void PhysicsWorld::removeRobot(RobotId id) {
  if (!hasRobot(id)) throw PhysicsError("no robot with id " + std::to_string(id));
  impl_->wakeTouching(impl_->robots[id].get());  // what rested on it falls
  impl_->removeFromWorld(impl_->robots[id].get());
  impl_->robots[id].reset();
}

void PhysicsWorld::step() {
  for (auto& r : impl_->robots)
    if (r) impl_->applyCommands(r.get());
  // A free body without joints: only an external wrench (apply_body_wrench) acts through it.
  for (auto& b : impl_->free_bodies) {
    if (b && (b->has_ext_wrench || b->has_gravity_free || !b->joints.empty())) impl_->applyCommands(b.get());
  }
  // maxSubSteps = 0: exactly one internal step of dt (no accumulator, no interpolation).
  impl_->world->stepSimulation(impl_->options.dt, 0, impl_->options.dt);
  ++impl_->steps;
  for (auto& r : impl_->robots)
    if (r) impl_->readEfforts(r.get());
  for (auto& b : impl_->free_bodies)
    if (b && !b->joints.empty()) impl_->readEfforts(b.get());
}

void PhysicsWorld::Impl::readEfforts(RobotState* r) {
  const double inv_dt = 1.0 / options.dt;
  for (std::size_t i = 0; i < r->joints.size(); ++i) {
    const RobotState::Command& c = r->commands[i];
    if (c.mode == RobotState::Mode::kEffort) {
      r->applied_effort[i] = c.effort;
    } else if (c.mode == RobotState::Mode::kVelocity) {
      btMultiBodyJointMotor* m = r->motors[i].get();
      r->applied_effort[i] = m && m->getNumRows() > 0 ? m->getAppliedImpulse(0) * inv_dt : 0.0;
    } else {
      r->applied_effort[i] = 0.0;
    }
  }
}

double PhysicsWorld::dt() const { return impl_->options.dt; }
double PhysicsWorld::time() const {
  return impl_->time_base + static_cast<double>(impl_->steps - impl_->step_base) * impl_->options.dt;
}
std::uint64_t PhysicsWorld::stepCount() const { return impl_->steps; }
void PhysicsWorld::resetTime() {
  impl_->steps = 0;
  impl_->step_base = 0;
  impl_->time_base = 0.0;
}

void PhysicsWorld::setTimeStep(double dt) {
  if (!(dt > 0.0 && dt <= kMaxTimeStep)) {
    throw PhysicsError("physics: time step must be in (0, " + std::to_string(kMaxTimeStep) +
                       "] s, got " + std::to_string(dt));
  }
  if (dt == impl_->options.dt) return;
  impl_->time_base = time();
  impl_->step_base = impl_->steps;
  impl_->options.dt = dt;
  impl_->world->getSolverInfo().m_timeStep = dt;
}

void PhysicsWorld::setGravity(const Eigen::Vector3d& g) {
  if (!g.allFinite() || g.cwiseAbs().maxCoeff() > kMaxGravity) {
    std::ostringstream os;
    os << "physics: gravity (" << g.transpose() << ") must be finite, each component <= "
       << kMaxGravity << " m/s^2";
    throw PhysicsError(os.str());
  }
  impl_->options.gravity = g;
  impl_->world->setGravity(toBt(g));
  // Bodies asleep would not feel the change.
  for (auto& r : impl_->robots)
    if (r) r->wake();
  for (auto& b : impl_->free_bodies)
    if (b) b->wake();
}

void PhysicsWorld::setSolverIterations(int iterations) {
  if (iterations < 1 || iterations > kMaxSolverIterations) {
    throw PhysicsError("physics: solver iterations must be in [1, " +
                       std::to_string(kMaxSolverIterations) + "], got " + std::to_string(iterations));
  }
  impl_->options.solver_iterations = iterations;
  impl_->world->getSolverInfo().m_numIterations = iterations;
}

void PhysicsWorld::setContactMaxCorrectingVel(double v) {
  if (!(v > 0.0) || !std::isfinite(v)) {
    throw PhysicsError("physics: contact_max_correcting_vel must be finite and > 0, got " +
                       std::to_string(v));
  }
  impl_->options.contact_max_correcting_vel = v;
  static_cast<MultiBodyWorld*>(impl_->world.get())->max_correcting_vel = v;
}

SolverSettings PhysicsWorld::solverSettings() const {
  const btContactSolverInfo& si = impl_->world->getSolverInfo();
  SolverSettings s;
  s.iterations = si.m_numIterations;
  s.sor = si.m_sor;
  s.residual_threshold = si.m_leastSquaresResidualThreshold;
  s.global_cfm = si.m_globalCfm;
  s.erp = si.m_erp2;
  return s;
}
int PhysicsWorld::robotCount() const { return static_cast<int>(impl_->robots.size()); }

PhysicsRobot& PhysicsWorld::robot(RobotId id) {
  return const_cast<PhysicsRobot&>(static_cast<const PhysicsWorld*>(this)->robot(id));
}
const PhysicsRobot& PhysicsWorld::robot(RobotId id) const {
  if (!hasRobot(id)) throw PhysicsError("no robot with id " + std::to_string(id));
  return impl_->robots[id]->handle;
}
bool PhysicsWorld::hasRobot(RobotId id) const {
  return id >= 0 && id < robotCount() && impl_->robots[id];
}
RobotId PhysicsWorld::robotId(const std::string& name) const {
  for (const auto& r : impl_->robots) {
    if (r && r->name == name) return r->id;
  }
  return -1;
}
const PhysicsOptions& PhysicsWorld::options() const { return impl_->options; }
btMultiBodyDynamicsWorld* PhysicsWorld::bulletWorld() { return impl_->world.get(); }

}  // namespace tianracer_sim
