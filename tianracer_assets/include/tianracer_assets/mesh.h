// Mesh files (STL, DAE, OBJ, ... anything assimp reads) as plain indexed triangle lists, placed
// the way Gazebo classic places them (docs/meshes.md: one rule per line, with its Gazebo source
// file), loaded once per source and shared by the simulator (collision, ray casting, rendering)
// and by tianracer_control (wheel sizing). ROS-free.
#ifndef TIANRACER_ASSETS_MESH_H
#define TIANRACER_ASSETS_MESH_H

#include <cstdint>
#include <map>
#include <memory>
#include <mutex>
#include <stdexcept>
#include <string>
#include <tuple>
#include <vector>

#include <Eigen/Core>

#include "tianracer_assets/diagnostic.h"

namespace tianracer_assets {

/// A mesh file that is missing, unreadable, empty or has no triangles. The message names the path.
using MeshError = InputError;  // diagnostic.h: the one error type of an input

/// A material of a mesh file (COLLADA <effect>, OBJ .mtl), as assimp reads it.
struct MeshMaterial {
  std::string name;
  bool has_diffuse = false;
  Eigen::Vector4f diffuse{1.0f, 1.0f, 1.0f, 1.0f};
  bool has_ambient = false;
  Eigen::Vector4f ambient{0.0f, 0.0f, 0.0f, 1.0f};
  std::string texture_uri;  // the diffuse texture as the file names it ("" = none)
  std::string texture;      // ... resolved to an existing file ("" when not found)
  std::string texture_error;  // why `texture_uri` did not resolve (names the paths tried)
};

/// What to load: a file, the part of it an SDF <submesh> names, and the SDF <mesh><scale>.
struct MeshSource {
  std::string path;
  Eigen::Vector3d scale = Eigen::Vector3d::Ones();
  /// "" = the whole file; else the triangles of the parts of that name (COLLADA <node name>,
  /// OBJ o/g name), as Gazebo's submeshes are named.
  std::string submesh;
  /// Move the submesh's bounding-box centre to the origin (SDF <submesh><center>), before the
  /// scale.
  bool center_submesh = false;
};

/// Triangles only (assimp triangulates polygons and drops points and lines), identical vertices
/// joined; in the mesh's frame: the file's nodes, unit and the source's submesh and scale
/// applied (Gazebo's placement, mesh.cpp).
struct TriangleMesh {
  std::vector<Eigen::Vector3f> vertices;
  std::vector<uint32_t> indices;  // 3 per triangle, into vertices

  // Filled by loadMeshFileWithMaterials only (rendering); the vertices above are then still
  // joined by position alone, so normals are smoothed across texture seams.
  std::vector<Eigen::Vector2f> corner_uvs;  // 3 per triangle, parallel to indices; empty = none
  std::vector<int> triangle_material;       // per triangle, into materials
  std::vector<MeshMaterial> materials;

  std::size_t triangleCount() const { return indices.size() / 3; }
  /// Axis-aligned bounds of the vertices (min, max).
  Eigen::Vector3f boundsMin() const;
  Eigen::Vector3f boundsMax() const;
};

/// Loads a source without caching. Throws MeshError naming the path (and the submesh).
TriangleMesh loadMesh(const MeshSource& source);
/// Loads the whole file `path`, scaled.
TriangleMesh loadMeshFile(const std::string& path,
                          const Eigen::Vector3d& scale = Eigen::Vector3d::Ones());

/// Loads `path` with its texture coordinates (first UV channel; OpenGL's convention, v up from
/// the bottom of the image) and materials. A diffuse texture is looked for as the file writes
/// it (file:// URIs and %20 decoded), relative to the mesh's folder, then by its file name in
/// the mesh's folder and in ../materials/textures (where Gazebo models keep them). Embedded
/// textures are not read (texture_error says so). Throws MeshError as loadMeshFile.
TriangleMesh loadMeshWithMaterials(const MeshSource& source);
TriangleMesh loadMeshFileWithMaterials(const std::string& path,
                                       const Eigen::Vector3d& scale = Eigen::Vector3d::Ones());

/// Thread-safe cache keyed by the source: each file is parsed once per scale and submesh.
class MeshCache {
 public:
  /// Returns the cached mesh, loading it on first use. Throws MeshError (not cached).
  std::shared_ptr<const TriangleMesh> get(const MeshSource& source);
  std::shared_ptr<const TriangleMesh> get(const std::string& path,
                                          const Eigen::Vector3d& scale = Eigen::Vector3d::Ones());
  /// The same through loadMeshWithMaterials (cached separately).
  std::shared_ptr<const TriangleMesh> getWithMaterials(const MeshSource& source);
  std::shared_ptr<const TriangleMesh> getWithMaterials(
      const std::string& path, const Eigen::Vector3d& scale = Eigen::Vector3d::Ones());
  std::size_t size() const;
  void clear();

  /// The process-wide cache the physics, the ray caster and the renderer share.
  static MeshCache& global();

 private:
  std::shared_ptr<const TriangleMesh> find(const MeshSource& source, bool materials);
  using Key = std::tuple<std::string, double, double, double, std::string, bool, bool>;
  mutable std::mutex mutex_;
  std::map<Key, std::shared_ptr<const TriangleMesh>> meshes_;
};

}  // namespace tianracer_assets

#endif  // TIANRACER_ASSETS_MESH_H
