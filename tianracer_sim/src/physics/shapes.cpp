#include "shapes.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include "tianracer_sim/mesh/mesh_loader.h"
#include <tianracer_assets/wheel_fit.h>

namespace tianracer_sim {

using tianracer_assets::fitWheel;
using tianracer_assets::WheelFit;

std::unique_ptr<btCollisionShape> makeBox(const Eigen::Vector3d& size, double margin,
                                          const std::string& what) {
  if (!(size.minCoeff() > 0.0)) throw PhysicsError(what + ": box sizes must be positive");
  auto box = std::make_unique<btBoxShape>(toBt(Eigen::Vector3d(0.5 * size)));
  box->setMargin(std::min(margin, 0.25 * size.minCoeff()));
  return box;
}

std::unique_ptr<btCollisionShape> makeCylinderZ(double radius, double length, double margin,
                                                const std::string& what) {
  if (!(radius > 0.0) || !(length > 0.0)) {
    throw PhysicsError(what + ": cylinder radius and length must be positive");
  }
  auto cyl = std::make_unique<btCylinderShapeZ>(btVector3(radius, radius, 0.5 * length));
  cyl->setMargin(std::min(margin, 0.25 * std::min(radius, length)));
  return cyl;
}

std::unique_ptr<btCollisionShape> makeSphere(double radius, const std::string& what) {
  if (!(radius > 0.0)) throw PhysicsError(what + ": sphere radius must be positive");
  return std::make_unique<btSphereShape>(radius);
}

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

std::unique_ptr<btCollisionShape> makePrimitive(const Shape& s, double margin,
                                                const std::string& what) {
  switch (s.type) {
    case ShapeType::kBox: return makeBox(s.size, margin, what);
    case ShapeType::kCylinder: return makeCylinderZ(s.radius, s.length, margin, what);
    case ShapeType::kSphere: return makeSphere(s.radius, what);
    case ShapeType::kPlane:
    case ShapeType::kMesh: break;
  }
  return nullptr;
}

namespace {

/// The mesh's triangles copied into `out` (Bullet's triangle shapes point into them).
void storeTriangles(const TriangleMesh& mesh, OwnedShape* out) {
  out->mesh_vertices.reserve(mesh.vertices.size() * 3);
  for (const auto& v : mesh.vertices) {
    out->mesh_vertices.insert(out->mesh_vertices.end(), {v.x(), v.y(), v.z()});
  }
  out->mesh_indices.assign(mesh.indices.begin(), mesh.indices.end());
  out->mesh_interface = std::make_unique<btTriangleIndexVertexArray>(
      static_cast<int>(mesh.triangleCount()), out->mesh_indices.data(), 3 * sizeof(int),
      static_cast<int>(mesh.vertices.size()), out->mesh_vertices.data(), 3 * sizeof(btScalar));
}

}  // namespace

void makeStaticShape(const StaticShape& st, double margin, OwnedShape* out) {
  const std::string what = "static shape '" + st.name + "'";
  const Shape& s = st.shape;
  if (!isFinite(s)) throw PhysicsError(what + ": non-finite size");
  switch (s.type) {
    case ShapeType::kBox:
    case ShapeType::kCylinder:
    case ShapeType::kSphere:
      out->shape = makePrimitive(s, margin, what);
      return;
    case ShapeType::kPlane:
      if (!(s.normal.norm() > 0.0)) throw PhysicsError(what + ": plane normal is zero");
      out->shape = std::make_unique<btStaticPlaneShape>(toBt(Eigen::Vector3d(s.normal.normalized())), 0.0);
      return;
    case ShapeType::kMesh: {
      const auto mesh = meshOf(s);
      storeTriangles(*mesh, out);
      out->shape = std::make_unique<btBvhTriangleMeshShape>(out->mesh_interface.get(), true);
      return;
    }
  }
  throw PhysicsError(what + ": unsupported shape type");
}

std::unique_ptr<btCollisionShape> makeLinkShape(const TreeBody& body, const CollisionGeometry& g,
                                                double margin, WheelShape wheel_shape,
                                                bool concave, const std::string& what,
                                                Eigen::Isometry3d* X_BS, bool* is_wheel,
                                                std::unique_ptr<OwnedShape>* mesh_out) {
  *X_BS = g.X_BG;
  *is_wheel = false;
  if (g.shape.type == ShapeType::kMesh && concave) {
    // The exact triangles in the geometry frame. No margin: the surface is where the mesh
    // says (a margin would lift everything resting on it by that much), as ODE's trimesh
    // and our static meshes (btBvhTriangleMeshShape) have none.
    const auto mesh = meshOf(g.shape);
    auto owned = std::make_unique<OwnedShape>();
    storeTriangles(*mesh, owned.get());
    auto gimpact = std::make_unique<MovableMeshShape>(owned->mesh_interface.get());
    gimpact->setMargin(0.0);
    gimpact->updateBound();
    *mesh_out = std::move(owned);
    return gimpact;
  }

  // Wheels: a round mesh (or a cylinder along the axis) on the child link of a joint that turns
  // for ever (continuous, or SDF's revolute without <limit>: pioneer2dx, create).
  const bool wheel_joint =
      body.parent >= 0 && (body.joint_type == TreeJointType::kContinuous ||
                           (body.joint_type == TreeJointType::kRevolute && !body.has_position_limits));
  WheelFit fit;
  std::vector<Eigen::Vector3d> verts_B;
  if (g.shape.type == ShapeType::kMesh) {
    const auto mesh = meshOf(g.shape);
    verts_B.reserve(mesh->vertices.size());
    for (const auto& v : mesh->vertices) verts_B.push_back(g.X_BG * v.cast<double>());
    if (wheel_joint && wheel_shape != WheelShape::kMeshHull) fit = fitWheel(verts_B, body.axis_B);
  } else if (g.shape.type == ShapeType::kCylinder && wheel_joint) {
    const Eigen::Vector3d cyl_axis = g.X_BG.linear().col(2);
    const Eigen::Vector3d c = g.X_BG.translation();
    const Eigen::Vector3d off = c - c.dot(body.axis_B) * body.axis_B;
    // Within 1 mrad and 0.1 mm of the axle: Gazebo's library writes pi/2 as 1.5707 (96 urad
    // short), which tilts a wheel's cylinder off its axle and moves it off by microns. The
    // fitted wheel sits on the axle.
    if (std::abs(std::abs(cyl_axis.dot(body.axis_B)) - 1.0) < 5e-7 && off.norm() < 1e-4) {
      fit.is_wheel = true;
      fit.radius = g.shape.radius;
      fit.width = g.shape.length;
      fit.center = c;
      fit.roundness = 1.0;
    }
  }
  *is_wheel = fit.is_wheel && wheel_shape != WheelShape::kMeshHull;
  if (*is_wheel) {
    X_BS->linear() = rotationYTo(body.axis_B);
    X_BS->translation() = fit.center;
    const double R = fit.radius, W = fit.width;
    switch (wheel_shape) {
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

  switch (g.shape.type) {
    case ShapeType::kBox:
    case ShapeType::kCylinder:
    case ShapeType::kSphere:
      return makePrimitive(g.shape, margin, what);
    case ShapeType::kPlane:
      throw PhysicsError(what + ": a plane cannot move with a body");
    case ShapeType::kMesh: {
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

}  // namespace tianracer_sim
