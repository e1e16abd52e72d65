#include "tianracer_sim/model/robot_meshes.h"

#include <set>
#include <string>
#include <utility>

#include <urdf_model/model.h>

#include "tianracer_sim/mesh/mesh_loader.h"

namespace tianracer_sim {

namespace {

// What the physics and the renderer load for a URDF mesh (physics/rigid_tree.cpp
// shapeFromUrdf: the resolved file and the <mesh scale>).
MeshSource sourceOf(const RobotModel& model, const urdf::Mesh& mesh, bool* resolved) {
  MeshSource source;
  const auto it = model.mesh_paths.find(mesh.filename);
  *resolved = it != model.mesh_paths.end();
  if (*resolved) source.path = it->second;
  source.scale = Eigen::Vector3d(mesh.scale.x, mesh.scale.y, mesh.scale.z);
  return source;
}

}  // namespace

int readRobotMeshes(const RobotModel& model, const WarningSink& warn) {
  if (!model.urdf) return 0;
  std::set<std::string> files;
  for (const auto& kv : model.urdf->links_) {
    const urdf::LinkSharedPtr& link = kv.second;
    if (!link) continue;
    for (const auto& c : link->collision_array) {
      if (!c || !c->geometry || c->geometry->type != urdf::Geometry::MESH) continue;
      const auto& mesh = static_cast<const urdf::Mesh&>(*c->geometry);
      bool resolved = false;
      const MeshSource source = sourceOf(model, mesh, &resolved);
      if (!resolved) continue;
      try {
        MeshCache::global().get(source);
        files.insert(source.path);
      } catch (const MeshError& e) {
        throw ModelError(model.source + ": link '" + link->name + "' collision mesh '" + mesh.filename +
                         "': " + e.what());
      }
    }
    for (const auto& v : link->visual_array) {
      if (!v || !v->geometry || v->geometry->type != urdf::Geometry::MESH) continue;
      const auto& mesh = static_cast<const urdf::Mesh&>(*v->geometry);
      bool resolved = false;
      const MeshSource source = sourceOf(model, mesh, &resolved);
      if (!resolved) continue;
      try {
        MeshCache::global().getWithMaterials(source);
        files.insert(source.path);
      } catch (const MeshError& e) {
        if (warn)
          warn(model.source + ": link '" + link->name + "' visual mesh '" + mesh.filename + "': " + e.what() +
               "; the renderer leaves it out");
      }
    }
  }
  return static_cast<int>(files.size());
}

}  // namespace tianracer_sim
