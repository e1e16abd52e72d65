#include "tianracer_sim/mesh/mesh_loader.h"

namespace tianracer_sim {

tianracer_assets::MeshSource meshSourceOf(const Shape& shape) {
  tianracer_assets::MeshSource source;
  source.path = shape.mesh_path;
  source.scale = shape.scale;
  source.submesh = shape.submesh;
  source.center_submesh = shape.center_submesh;
  return source;
}

std::shared_ptr<const TriangleMesh> meshOf(const Shape& shape) {
  return MeshCache::global().get(meshSourceOf(shape));
}

std::shared_ptr<const TriangleMesh> meshWithMaterialsOf(const Shape& shape) {
  return MeshCache::global().getWithMaterials(meshSourceOf(shape));
}

}  // namespace tianracer_sim
