#include "tianracer_assets/mesh.h"

#include <sys/stat.h>

#include <array>
#include <cctype>
#include <cmath>
#include <limits>
#include <map>
#include <string>

#include <assimp/Importer.hpp>
#include <assimp/postprocess.h>
#include <assimp/scene.h>

namespace tianracer_assets {

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

namespace {

void checkFile(const std::string& path, const Eigen::Vector3d& scale) {
  struct stat st {};
  if (path.empty()) throw MeshError("mesh: empty path");
  if (::stat(path.c_str(), &st) != 0) throw MeshError("mesh '" + path + "': file not found");
  if (!S_ISREG(st.st_mode)) throw MeshError("mesh '" + path + "': not a regular file");
  if (st.st_size == 0) throw MeshError("mesh '" + path + "': file is empty");
  if (!scale.allFinite() || scale.minCoeff() <= 0.0) {
    throw MeshError("mesh '" + path + "': scale must be finite and positive");
  }
}

[[noreturn]] void importFailed(const std::string& path, const Assimp::Importer& importer) {
  // assimp drops points and lines on import, so a file with no triangles fails as
  // "No meshes remaining": say what that means for the user.
  const std::string why = importer.GetErrorString();
  if (why.find("No meshes remaining") != std::string::npos)
    throw MeshError("mesh '" + path + "': no triangles (assimp: " + why + ")");
  throw MeshError("mesh '" + path + "': unreadable (" + why + ")");
}

void checkResult(const std::string& path, const TriangleMesh& mesh) {
  if (mesh.vertices.empty()) throw MeshError("mesh '" + path + "': no vertices");
  if (mesh.indices.empty()) throw MeshError("mesh '" + path + "': no triangles");
  for (const auto& v : mesh.vertices) {
    if (!v.allFinite()) throw MeshError("mesh '" + path + "': non-finite vertex");
  }
}

bool isFile(const std::string& p) {
  struct stat st {};
  return ::stat(p.c_str(), &st) == 0 && S_ISREG(st.st_mode);
}

std::string dirOf(const std::string& path) {
  const auto slash = path.find_last_of('/');
  return slash == std::string::npos ? "." : path.substr(0, slash);
}

// "file:///a%20b.png" -> "/a b.png"; other text unchanged.
std::string uriToPath(std::string uri) {
  if (uri.rfind("file://", 0) == 0) uri = uri.substr(7);
  std::string out;
  for (std::size_t i = 0; i < uri.size(); ++i) {
    if (uri[i] == '%' && i + 2 < uri.size() && std::isxdigit(static_cast<unsigned char>(uri[i + 1])) &&
        std::isxdigit(static_cast<unsigned char>(uri[i + 2]))) {
      out += static_cast<char>(std::stoi(uri.substr(i + 1, 2), nullptr, 16));
      i += 2;
    } else {
      out += uri[i] == '\\' ? '/' : uri[i];
    }
  }
  return out;
}

void resolveTexture(const std::string& mesh_path, MeshMaterial* m) {
  if (m->texture_uri.empty()) return;
  if (m->texture_uri[0] == '*') {
    m->texture_error = "texture '" + m->texture_uri + "' is embedded in the mesh file (not supported)";
    return;
  }
  const std::string p = uriToPath(m->texture_uri);
  const std::string dir = dirOf(mesh_path);
  const auto slash = p.find_last_of('/');
  const std::string base = slash == std::string::npos ? p : p.substr(slash + 1);
  std::vector<std::string> tried;
  tried.push_back(!p.empty() && p[0] == '/' ? p : dir + "/" + p);
  tried.push_back(dir + "/" + base);
  tried.push_back(dir + "/../materials/textures/" + base);
  for (const std::string& t : tried) {
    if (isFile(t)) {
      m->texture = t;
      return;
    }
  }
  m->texture_error = "texture '" + m->texture_uri + "' not found (tried";
  for (const std::string& t : tried) m->texture_error += " " + t;
  m->texture_error += ")";
}

// Appends the triangles of `node` and its children with UVs and material indices; vertices
// are joined by exact position.
void collectWithMaterials(const aiScene* scene, const aiNode* node, const aiMatrix4x4& parent,
                          const Eigen::Vector3d& scale,
                          std::map<std::array<float, 3>, uint32_t>* joined, bool* any_uv,
                          TriangleMesh* out) {
  const aiMatrix4x4 T = parent * node->mTransformation;
  for (unsigned m = 0; m < node->mNumMeshes; ++m) {
    const aiMesh* mesh = scene->mMeshes[node->mMeshes[m]];
    std::vector<uint32_t> index(mesh->mNumVertices);
    for (unsigned v = 0; v < mesh->mNumVertices; ++v) {
      const aiVector3D p = T * mesh->mVertices[v];
      const std::array<float, 3> key = {static_cast<float>(p.x * scale.x()),
                                        static_cast<float>(p.y * scale.y()),
                                        static_cast<float>(p.z * scale.z())};
      const auto it = joined->emplace(key, static_cast<uint32_t>(out->vertices.size()));
      if (it.second) out->vertices.emplace_back(key[0], key[1], key[2]);
      index[v] = it.first->second;
    }
    const aiVector3D* uv = mesh->HasTextureCoords(0) ? mesh->mTextureCoords[0] : nullptr;
    if (uv) *any_uv = true;
    for (unsigned f = 0; f < mesh->mNumFaces; ++f) {
      const aiFace& face = mesh->mFaces[f];
      if (face.mNumIndices != 3) continue;
      for (int k = 0; k < 3; ++k) {
        out->indices.push_back(index[face.mIndices[k]]);
        const aiVector3D t = uv ? uv[face.mIndices[k]] : aiVector3D(0, 0, 0);
        out->corner_uvs.emplace_back(t.x, t.y);
      }
      out->triangle_material.push_back(static_cast<int>(mesh->mMaterialIndex));
    }
  }
  for (unsigned c = 0; c < node->mNumChildren; ++c) {
    collectWithMaterials(scene, node->mChildren[c], T, scale, joined, any_uv, out);
  }
}

}  // namespace

TriangleMesh loadMeshFile(const std::string& path, const Eigen::Vector3d& scale) {
  checkFile(path, scale);
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
  if (scene == nullptr || scene->mRootNode == nullptr) importFailed(path, importer);
  TriangleMesh mesh;
  collect(scene, scene->mRootNode, aiMatrix4x4(), scale, &mesh);
  checkResult(path, mesh);
  return mesh;
}

TriangleMesh loadMeshFileWithMaterials(const std::string& path, const Eigen::Vector3d& scale) {
  checkFile(path, scale);
  Assimp::Importer importer;
  importer.SetPropertyInteger(AI_CONFIG_PP_SBP_REMOVE, aiPrimitiveType_POINT | aiPrimitiveType_LINE);
  importer.SetPropertyInteger(AI_CONFIG_PP_RVC_FLAGS,
                              aiComponent_NORMALS | aiComponent_TANGENTS_AND_BITANGENTS |
                                  aiComponent_COLORS | aiComponent_BONEWEIGHTS |
                                  aiComponent_ANIMATIONS | aiComponent_LIGHTS | aiComponent_CAMERAS);
  const aiScene* scene = importer.ReadFile(
      path, aiProcess_RemoveComponent | aiProcess_Triangulate | aiProcess_JoinIdenticalVertices |
                aiProcess_SortByPType);
  if (scene == nullptr || scene->mRootNode == nullptr) importFailed(path, importer);
  TriangleMesh mesh;
  std::map<std::array<float, 3>, uint32_t> joined;
  bool any_uv = false;
  collectWithMaterials(scene, scene->mRootNode, aiMatrix4x4(), scale, &joined, &any_uv, &mesh);
  checkResult(path, mesh);
  if (!any_uv) mesh.corner_uvs.clear();
  for (unsigned i = 0; i < scene->mNumMaterials; ++i) {
    const aiMaterial* am = scene->mMaterials[i];
    MeshMaterial m;
    aiString name;
    if (am->Get(AI_MATKEY_NAME, name) == AI_SUCCESS) m.name = name.C_Str();
    aiColor4D c;
    if (am->Get(AI_MATKEY_COLOR_DIFFUSE, c) == AI_SUCCESS) {
      m.has_diffuse = true;
      m.diffuse = Eigen::Vector4f(c.r, c.g, c.b, c.a);
    }
    if (am->Get(AI_MATKEY_COLOR_AMBIENT, c) == AI_SUCCESS) {
      m.has_ambient = true;
      m.ambient = Eigen::Vector4f(c.r, c.g, c.b, c.a);
    }
    aiString tex;
    if (am->GetTextureCount(aiTextureType_DIFFUSE) > 0 &&
        am->GetTexture(aiTextureType_DIFFUSE, 0, &tex) == AI_SUCCESS) {
      m.texture_uri = tex.C_Str();
      resolveTexture(path, &m);
    }
    mesh.materials.push_back(m);
  }
  for (int& t : mesh.triangle_material) {
    if (t < 0 || t >= static_cast<int>(mesh.materials.size())) t = -1;
  }
  return mesh;
}

std::shared_ptr<const TriangleMesh> MeshCache::get(const std::string& path,
                                                   const Eigen::Vector3d& scale) {
  const Key key{path, scale.x(), scale.y(), scale.z(), false};
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

std::shared_ptr<const TriangleMesh> MeshCache::getWithMaterials(const std::string& path,
                                                                const Eigen::Vector3d& scale) {
  const Key key{path, scale.x(), scale.y(), scale.z(), true};
  {
    std::lock_guard<std::mutex> lock(mutex_);
    auto it = meshes_.find(key);
    if (it != meshes_.end()) return it->second;
  }
  auto mesh = std::make_shared<const TriangleMesh>(loadMeshFileWithMaterials(path, scale));
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

}  // namespace tianracer_assets
