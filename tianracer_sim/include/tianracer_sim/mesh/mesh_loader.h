// The simulator's meshes: a mesh Shape as every consumer places it (physics, ray casting,
// rendering, robot placement), through tianracer_assets' loader and its one process-wide cache.
// ROS-free.
#ifndef TIANRACER_SIM_MESH_MESH_LOADER_H
#define TIANRACER_SIM_MESH_MESH_LOADER_H

#include <memory>

#include <tianracer_assets/mesh.h>

#include "tianracer_sim/geometry/shape.h"

namespace tianracer_sim {

using tianracer_assets::loadMeshFile;
using tianracer_assets::loadMeshFileWithMaterials;
using tianracer_assets::MeshCache;
using tianracer_assets::MeshError;
using tianracer_assets::MeshMaterial;
using tianracer_assets::MeshSource;
using tianracer_assets::TriangleMesh;

/// What a kMesh shape loads: its file, scale and submesh.
tianracer_assets::MeshSource meshSourceOf(const Shape& shape);

/// The triangles of a kMesh shape (its file's parts, placed as Gazebo places them, scaled), from
/// MeshCache::global(). Throws MeshError naming the file.
std::shared_ptr<const TriangleMesh> meshOf(const Shape& shape);

/// The same with texture coordinates and materials (rendering), cached separately.
std::shared_ptr<const TriangleMesh> meshWithMaterialsOf(const Shape& shape);

}  // namespace tianracer_sim

#endif  // TIANRACER_SIM_MESH_MESH_LOADER_H
