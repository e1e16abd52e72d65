// Internal: Bullet collision shapes for static shapes and robot links (primitives, convex hulls
// of meshes, fitted wheels, triangle meshes static and moving).
#ifndef TIANRACER_SIM_PHYSICS_SHAPES_H
#define TIANRACER_SIM_PHYSICS_SHAPES_H

#include <memory>
#include <string>
#include <vector>

#include "bullet.h"
#include "tianracer_sim/physics/rigid_tree.h"
#include "tianracer_sim/physics/world.h"

namespace tianracer_sim {

/// Primitives with Bullet's margin kept inside the shape (at most `margin`, a quarter of the
/// smallest extent). Throw PhysicsError "<what>: ..." for non-positive sizes.
std::unique_ptr<btCollisionShape> makeBox(const Eigen::Vector3d& size, double margin,
                                          const std::string& what);
std::unique_ptr<btCollisionShape> makeCylinderZ(double radius, double length, double margin,
                                                const std::string& what);
std::unique_ptr<btCollisionShape> makeSphere(double radius, const std::string& what);

/// Convex hull of `points` whose faces are moved inwards by `margin`, so that hull + margin is
/// the original hull (Bullet adds the margin outwards; its default 4 cm would swallow a wheel).
std::unique_ptr<btConvexHullShape> makeHull(const std::vector<btVector3>& points, double margin);

/// A Bullet shape and the storage a triangle mesh shape points into (do not move once built).
struct OwnedShape {
  std::unique_ptr<btCollisionShape> shape;
  std::unique_ptr<btTriangleIndexVertexArray> mesh_interface;
  std::vector<btScalar> mesh_vertices;
  std::vector<int> mesh_indices;
};

/// How near a movable mesh's triangles and a static mesh's are paired (m): more than a body
/// falls in one step at 1 ms (3 mm from 0.5 m), so that meshes meet before they cross.
constexpr btScalar kMeshPairPad = 0.005;

/// A movable concave mesh: GImpact with no margin (as ODE's trimesh), whose AABB is padded by
/// kMeshPairPad. A flat mesh's AABB has no thickness, and Bullet drops a compound's child whose
/// AABB misses the other object's (btCompoundCollisionAlgorithm), so a flat plate that sank by
/// a step's fall below a flat static mesh was never collided with it (issue 40). Only the
/// pairing sees the pad: contacts are found from the triangles themselves.
class MovableMeshShape : public btGImpactMeshShape {
 public:
  using btGImpactMeshShape::btGImpactMeshShape;
  void getAabb(const btTransform& t, btVector3& aabb_min, btVector3& aabb_max) const override {
    btGImpactMeshShape::getAabb(t, aabb_min, aabb_max);
    aabb_min -= btVector3(kMeshPairPad, kMeshPairPad, kMeshPairPad);
    aabb_max += btVector3(kMeshPairPad, kMeshPairPad, kMeshPairPad);
  }
};

/// A box, cylinder or sphere; nullptr for a plane or a mesh.
std::unique_ptr<btCollisionShape> makePrimitive(const Shape& s, double margin,
                                                const std::string& what);

/// The shape of a static body: primitives, a plane, or the exact triangle mesh.
void makeStaticShape(const StaticShape& s, double margin, OwnedShape* out);

/// The shape of one collision of a robot body, placed at X_BS in the body frame. A mesh (or a
/// cylinder along the axis) on the child of a continuous joint that fits a wheel gets
/// `wheel_shape` (*is_wheel set unless that is kMeshHull); other meshes become hulls, or with
/// `concave` (world models) keep their triangles: a MovableMeshShape (GImpact) with no margin (as ODE's
/// trimesh in Gazebo), its triangles in the geometry frame and stored in *mesh.
std::unique_ptr<btCollisionShape> makeLinkShape(const TreeBody& body, const CollisionGeometry& g,
                                                double margin, WheelShape wheel_shape,
                                                bool concave, const std::string& what,
                                                Eigen::Isometry3d* X_BS, bool* is_wheel,
                                                std::unique_ptr<OwnedShape>* mesh);

}  // namespace tianracer_sim

#endif  // TIANRACER_SIM_PHYSICS_SHAPES_H
