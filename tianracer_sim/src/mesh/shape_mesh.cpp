#include "tianracer_sim/mesh/mesh_loader.h"

namespace tianracer_sim {

std::shared_ptr<const TriangleMesh> meshOf(const Shape& shape) {
  return MeshCache::global().get(shape.mesh_path, shape.scale);
}

std::shared_ptr<const TriangleMesh> meshWithMaterialsOf(const Shape& shape) {
  return MeshCache::global().getWithMaterials(shape.mesh_path, shape.scale);
}

}  // namespace tianracer_sim
