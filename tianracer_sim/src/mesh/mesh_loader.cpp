#include "tianracer_sim/mesh/mesh_loader.h"

#include <sys/stat.h>

#include <cmath>
#include <limits>

#include <assimp/Importer.hpp>
#include <assimp/postprocess.h>
#include <assimp/scene.h>

namespace tianracer_sim {

Eigen::Vector3f TriangleMesh::boundsMin() const {
  Eigen::Vector3f lo = Eigen::Vector3f::Constant(std::numeric_limits<float>::infinity());
  for (const auto& v : vertices) lo = lo.cwiseMin(v);
  return lo;
}

Eigen::Vector3f TriangleMesh::boundsMax() const {
  Eigen::Vector3f hi = Eigen::Vector3f::Constant(-std::numeric_limits<float>::infinity());
  for (const auto& v : vertices) hi = hi.cwiseMax(v);
  return hi;
}

namespace {

// Appends the triangles of `node` and its children, with the accumulated node transform
// (aiProcess_PreTransformVertices would also do this, but it drops meshes used twice).
void collect(const aiScene* scene, const aiNode* node, const aiMatrix4x4& parent,
             const Eigen::Vector3d& scale, TriangleMesh* out) {
  const aiMatrix4x4 T = parent * node->mTransformation;
  for (unsigned m = 0; m < node->mNumMeshes; ++m) {
    const aiMesh* mesh = scene->mMeshes[node->mMeshes[m]];
    const auto base = static_cast<uint32_t>(out->vertices.size());
    for (unsigned v = 0; v < mesh->mNumVertices; ++v) {
      const aiVector3D p = T * mesh->mVertices[v];
      out->vertices.emplace_back(static_cast<float>(p.x * scale.x()),
                                 static_cast<float>(p.y * scale.y()),
                                 static_cast<float>(p.z * scale.z()));
    }
    for (unsigned f = 0; f < mesh->mNumFaces; ++f) {
      const aiFace& face = mesh->mFaces[f];
      if (face.mNumIndices != 3) continue;  // points and lines left by SortByPType
      for (int k = 0; k < 3; ++k) out->indices.push_back(base + face.mIndices[k]);
    }
  }
  for (unsigned c = 0; c < node->mNumChildren; ++c) collect(scene, node->mChildren[c], T, scale, out);
}

}  // namespace

TriangleMesh loadMeshFile(const std::string& path, const Eigen::Vector3d& scale) {
  struct stat st {};
  if (path.empty()) throw MeshError("mesh: empty path");
  if (::stat(path.c_str(), &st) != 0) throw MeshError("mesh '" + path + "': file not found");
  if (!S_ISREG(st.st_mode)) throw MeshError("mesh '" + path + "': not a regular file");
  if (st.st_size == 0) throw MeshError("mesh '" + path + "': file is empty");
  if (!scale.allFinite() || scale.minCoeff() <= 0.0) {
    throw MeshError("mesh '" + path + "': scale must be finite and positive");
  }

  Assimp::Importer importer;
  // Only positions are kept: dropping STL's per-facet normals (and UVs, colours) first lets
  // JoinIdenticalVertices merge the corners that facets share.
  importer.SetPropertyInteger(AI_CONFIG_PP_SBP_REMOVE, aiPrimitiveType_POINT | aiPrimitiveType_LINE);
  importer.SetPropertyInteger(AI_CONFIG_PP_RVC_FLAGS,
                              aiComponent_NORMALS | aiComponent_TANGENTS_AND_BITANGENTS |
                                  aiComponent_COLORS | aiComponent_TEXCOORDS |
                                  aiComponent_BONEWEIGHTS | aiComponent_ANIMATIONS |
                                  aiComponent_TEXTURES | aiComponent_LIGHTS | aiComponent_CAMERAS |
                                  aiComponent_MATERIALS);
  const aiScene* scene = importer.ReadFile(
      path, aiProcess_RemoveComponent | aiProcess_Triangulate | aiProcess_JoinIdenticalVertices |
                aiProcess_SortByPType);
  if (scene == nullptr || scene->mRootNode == nullptr) {
    // assimp drops points and lines on import, so a file with no triangles fails as
    // "No meshes remaining": say what that means for the user.
    const std::string why = importer.GetErrorString();
    if (why.find("No meshes remaining") != std::string::npos)
      throw MeshError("mesh '" + path + "': no triangles (assimp: " + why + ")");
    throw MeshError("mesh '" + path + "': unreadable (" + why + ")");
  }
  TriangleMesh mesh;
  collect(scene, scene->mRootNode, aiMatrix4x4(), scale, &mesh);
  if (mesh.vertices.empty()) throw MeshError("mesh '" + path + "': no vertices");
  if (mesh.indices.empty()) throw MeshError("mesh '" + path + "': no triangles");
  for (const auto& v : mesh.vertices) {
    if (!v.allFinite()) throw MeshError("mesh '" + path + "': non-finite vertex");
  }
  return mesh;
}

std::shared_ptr<const TriangleMesh> MeshCache::get(const std::string& path,
                                                   const Eigen::Vector3d& scale) {
  const Key key{path, scale.x(), scale.y(), scale.z()};
  {
    std::lock_guard<std::mutex> lock(mutex_);
    auto it = meshes_.find(key);
    if (it != meshes_.end()) return it->second;
  }
  // Parse outside the lock; if two threads race, the first insert wins (same content).
  auto mesh = std::make_shared<const TriangleMesh>(loadMeshFile(path, scale));
  std::lock_guard<std::mutex> lock(mutex_);
  return meshes_.emplace(key, std::move(mesh)).first->second;
}

std::size_t MeshCache::size() const {
  std::lock_guard<std::mutex> lock(mutex_);
  return meshes_.size();
}

void MeshCache::clear() {
  std::lock_guard<std::mutex> lock(mutex_);
  meshes_.clear();
}

MeshCache& MeshCache::global() {
  static MeshCache cache;
  return cache;
}

}  // namespace tianracer_sim
