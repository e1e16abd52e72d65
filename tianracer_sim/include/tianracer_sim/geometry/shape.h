// The one geometry type: what a world's <geometry>, a URDF <collision>/<visual>, a physics body and
// a sensor's scene item are made of. Header-only, no dependency but Eigen, so the world parser,
// the rigid tree, the physics, the ray caster and the renderer share it without converting.
#ifndef TIANRACER_SIM_GEOMETRY_SHAPE_H
#define TIANRACER_SIM_GEOMETRY_SHAPE_H

#include <cmath>
#include <string>

#include <Eigen/Geometry>

namespace tianracer_sim {

enum class ShapeType { kBox, kCylinder, kSphere, kPlane, kMesh };

/// One geometric primitive in its own frame S.
///  - box: full extents `size` (x, y, z), centred;
///  - cylinder: `radius`, `length` along S's z axis, centred;
///  - sphere: `radius`;
///  - plane: infinite plane through S's origin with normal `normal` (S frame), `size` x/y is the
///    visual extent (0 = unbounded);
///  - mesh: `mesh_path` (absolute, resolved), scaled component-wise by `scale`; `submesh` (an
///    SDF <submesh><name>) keeps only the file's parts of that name, `center_submesh` centres
///    them on S's origin first (mesh/mesh_loader.h places every mesh so).
struct Shape {
  ShapeType type = ShapeType::kBox;
  Eigen::Vector3d size = Eigen::Vector3d::Zero();
  double radius = 0.0;
  double length = 0.0;
  Eigen::Vector3d normal = Eigen::Vector3d::UnitZ();
  std::string mesh_path;
  Eigen::Vector3d scale = Eigen::Vector3d::Ones();
  std::string submesh;
  bool center_submesh = false;
};

/// True when every number of the shape is finite (what a physics or sensor backend may build).
inline bool isFinite(const Shape& s) {
  return s.size.allFinite() && std::isfinite(s.radius) && std::isfinite(s.length) &&
         s.normal.allFinite() && s.scale.allFinite();
}

}  // namespace tianracer_sim

#endif  // TIANRACER_SIM_GEOMETRY_SHAPE_H
