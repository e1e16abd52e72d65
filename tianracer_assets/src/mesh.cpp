#include "tianracer_assets/mesh.h"

#include <sys/stat.h>

#include <algorithm>
#include <array>
#include <cctype>
#include <cmath>
#include <cstring>
#include <limits>
#include <map>
#include <sstream>
#include <string>

#include <assimp/DefaultIOSystem.h>
#include <assimp/Importer.hpp>
#include <assimp/postprocess.h>
#include <assimp/scene.h>
#include <tinyxml2.h>

#include "mesh_check.h"

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

// Where each piece of a file lands (mesh.h, docs/meshes.md). The rules are Gazebo classic's;
// the file named after each is where Gazebo applies it:
//  - COLLADA <asset><unit meter>: every vertex times `meter` (gazebo/common/ColladaLoader.cc,
//    Load: mesh->Scale(meter)). assimp 5.2's COLLADA importer applies it to the root node
//    (it has no switch to turn that off).
//  - COLLADA <up_axis>: ignored. Gazebo's ColladaLoader.cc never reads it (gazebo-classic issue
//    #1305, open): a Z_UP file from Blender stands as drawn and a Y_UP file lies on its side.
//    assimp turns Z_UP and X_UP files into Y_UP unless told not to:
//    AI_CONFIG_IMPORT_COLLADA_IGNORE_UP_DIRECTION (readScene).
//  - COLLADA nodes: <matrix>, <translate>, <rotate>, <scale> and <instance_node>, composed from
//    the scene root down (ColladaLoader.cc LoadNode / LoadNodeTransform); assimp keeps them as
//    aiNode transforms, applied here per instance (instances()).
//  - COLLADA geometry instanced by several nodes: every instance at its own node. Gazebo 11
//    differs: LoadPositions caches a source's transformed positions by id, so the later
//    instances land on the first one (gazebo-classic issue #2940, open). We follow COLLADA.
//  - STL, ASCII or binary (gazebo/common/STLLoader.cc tries ASCII, then binary; assimp tells
//    them apart by the file size, so a binary file whose header starts with "solid" is binary
//    here too): the numbers as written, in metres, one part without a name.
//  - OBJ with .mtl (gazebo/common/OBJLoader.cc, tinyobjloader): vertices as written; the
//    mtllib file next to the .obj gives the materials; each o/g group is a part named after
//    it (assimp names its node so).
//  - SDF <mesh><scale>: per axis, about the mesh origin, after all of the above
//    (gazebo/physics/ode/ODEMesh.cc scales the collision vertices, gazebo/rendering/Visual.cc
//    the scene node).
//  - SDF <submesh><name>: only the parts of that name (gazebo/physics/MeshShape.cc takes
//    mesh->GetSubMesh(name), gazebo/rendering/Visual.cc InsertMesh draws every submesh of that
//    name); <center>true: the part's bounding box centred on the origin before the scale
//    (SubMesh::Center(Zero) in both). Gazebo's collision uses the whole mesh when no part has
//    the name while its visual shows nothing; here it is an error naming the parts there are.
// The file name given to a COLLADA <image> that names none (colladaWithImagePlaceholders).
constexpr const char* kNoImage = "tianracer-no-image:";

struct Instance {
  const aiMesh* mesh;
  aiMatrix4x4 T;  // node transforms from the scene root (unit included)
};

// The mesh instances of `node` and its children in depth-first order, each with its
// accumulated node transform; with a submesh name, only those of nodes of that name.
// (aiProcess_PreTransformVertices would also apply the transforms, but drops meshes used twice.)
// The part name of a node: its own name, or for a node without one (assimp calls it
// "$ColladaAutoName$_<n>") its parent's part. Gazebo names a COLLADA submesh after the last
// <node name> its loader entered (ColladaLoader.cc, currentNodeName), which for geometry in an
// unnamed child node is the named parent's: Blender and 3ds Max write files so.
std::string partName(const aiNode* node, const std::string& parent_part) {
  const std::string name = node->mName.C_Str();
  return name.rfind("$ColladaAutoName$", 0) == 0 ? parent_part : name;
}

// The mesh instances of `node` and its children in depth-first order, each with its
// accumulated node transform; with a submesh name, only those of parts of that name.
// (aiProcess_PreTransformVertices would also apply the transforms, but drops meshes used twice.)
void instances(const aiScene* scene, const aiNode* node, const aiMatrix4x4& parent,
               const std::string& parent_part, const std::string& submesh,
               std::vector<Instance>* out) {
  const aiMatrix4x4 T = parent * node->mTransformation;
  const std::string part = partName(node, parent_part);
  if (submesh.empty() || submesh == part) {
    for (unsigned m = 0; m < node->mNumMeshes; ++m) out->push_back({scene->mMeshes[node->mMeshes[m]], T});
  }
  for (unsigned c = 0; c < node->mNumChildren; ++c)
    instances(scene, node->mChildren[c], T, part, submesh, out);
}

// The names of the parts that hold triangles: what a <submesh> can name.
void partNames(const aiScene* scene, const aiNode* node, const std::string& parent_part,
               std::vector<std::string>* out) {
  const std::string part = partName(node, parent_part);
  bool triangles = false;
  for (unsigned m = 0; m < node->mNumMeshes; ++m)
    triangles = triangles || (scene->mMeshes[node->mMeshes[m]]->mPrimitiveTypes & aiPrimitiveType_TRIANGLE);
  if (triangles && std::find(out->begin(), out->end(), part) == out->end()) out->push_back(part);
  for (unsigned c = 0; c < node->mNumChildren; ++c) partNames(scene, node->mChildren[c], part, out);
}

// The instances a source places, and the offset its <center> subtracts (zero without).
std::vector<Instance> select(const aiScene* scene, const MeshSource& source, aiVector3D* offset) {
  std::vector<Instance> out;
  instances(scene, scene->mRootNode, aiMatrix4x4(), "", source.submesh, &out);
  if (!source.submesh.empty() && out.empty()) {
    std::vector<std::string> names;
    partNames(scene, scene->mRootNode, "", &names);
    std::string list;
    for (const std::string& n : names) list += (list.empty() ? "'" : ", '") + n + "'";
    throw MeshError("mesh '" + source.path + "': no submesh '" + source.submesh + "' (its parts: " +
                    (list.empty() ? std::string("none") : list) + ")");
  }
  *offset = aiVector3D(0, 0, 0);
  if (source.center_submesh && !source.submesh.empty()) {
    aiVector3D lo(std::numeric_limits<float>::infinity()), hi(-std::numeric_limits<float>::infinity());
    for (const Instance& in : out) {
      for (unsigned v = 0; v < in.mesh->mNumVertices; ++v) {
        const aiVector3D p = in.T * in.mesh->mVertices[v];
        lo = aiVector3D(std::min(lo.x, p.x), std::min(lo.y, p.y), std::min(lo.z, p.z));
        hi = aiVector3D(std::max(hi.x, p.x), std::max(hi.y, p.y), std::max(hi.z, p.z));
      }
    }
    if (lo.x <= hi.x) *offset = (lo + hi) * 0.5f;
  }
  return out;
}

// A vertex as it lands: node transforms, the <center> offset, then the <scale>.
std::array<float, 3> place(const Instance& in, unsigned v, const aiVector3D& offset,
                           const Eigen::Vector3d& scale) {
  const aiVector3D p = in.T * in.mesh->mVertices[v];
  return {static_cast<float>((p.x - offset.x) * scale.x()),
          static_cast<float>((p.y - offset.y) * scale.y()),
          static_cast<float>((p.z - offset.z) * scale.z())};
}

// Appends the triangles of the instances.
void collect(const std::vector<Instance>& parts, const aiVector3D& offset,
             const Eigen::Vector3d& scale, TriangleMesh* out) {
  for (const Instance& in : parts) {
    const aiMesh* mesh = in.mesh;
    const auto base = static_cast<uint32_t>(out->vertices.size());
    for (unsigned v = 0; v < mesh->mNumVertices; ++v) {
      const std::array<float, 3> p = place(in, v, offset, scale);
      out->vertices.emplace_back(p[0], p[1], p[2]);
    }
    for (unsigned f = 0; f < mesh->mNumFaces; ++f) {
      const aiFace& face = mesh->mFaces[f];
      if (face.mNumIndices != 3) continue;  // points and lines left by SortByPType
      for (int k = 0; k < 3; ++k) out->indices.push_back(base + face.mIndices[k]);
    }
  }
}

}  // namespace

namespace {

void checkFile(const std::string& path, const Eigen::Vector3d& scale) {
  if (path.empty()) throw MeshError("mesh: empty path");
  // stat() before open(): a directory or device names no mesh, and reading /dev/zero or a
  // fifo would never end.
  const std::string problem = mesh_check::fileProblem(path);
  if (!problem.empty()) throw MeshError("mesh '" + path + "': " + problem);
  struct stat st {};
  ::stat(path.c_str(), &st);
  if (st.st_size == 0) throw MeshError("mesh '" + path + "': file is empty");
  if (static_cast<std::uint64_t>(st.st_size) > mesh_check::kMaxFileBytes) {
    throw MeshError("mesh '" + path + "': " + std::to_string(st.st_size) + " bytes, above the limit of " +
                    std::to_string(mesh_check::kMaxFileBytes) + " bytes (256 MiB) for a mesh file");
  }
  if (!scale.allFinite() || scale.minCoeff() <= 0.0) {
    throw MeshError("mesh '" + path + "': scale must be finite and positive");
  }
}

// assimp's file system, refusing what is not a regular file: an OBJ's mtllib naming a fifo or
// /dev/zero would otherwise block or read without end.
class RegularFilesOnly : public Assimp::DefaultIOSystem {
 public:
  bool Exists(const char* file) const override {
    return mesh_check::fileProblem(file).empty() && Assimp::DefaultIOSystem::Exists(file);
  }
  Assimp::IOStream* Open(const char* file, const char* mode) override {
    if (!mesh_check::fileProblem(file).empty()) return nullptr;
    return Assimp::DefaultIOSystem::Open(file, mode);
  }
};

[[noreturn]] void importFailed(const std::string& path, const Assimp::Importer& importer) {
  // assimp drops points and lines on import, so a file with no triangles fails as
  // "No meshes remaining": say what that means for the user.
  const std::string why = importer.GetErrorString();
  if (why.find("No meshes remaining") != std::string::npos)
    throw MeshError("mesh '" + path + "': no triangles (assimp: " + why + ")");
  throw MeshError("mesh '" + path + "': unreadable (" + why + ")");
}

void checkResult(const std::string& path, const TriangleMesh& mesh) {
  if (mesh.vertices.empty()) throw MeshError("mesh '" + path + "': no triangles: the file holds no geometry");
  if (mesh.indices.empty()) throw MeshError("mesh '" + path + "': no triangles");
  for (std::size_t i = 0; i < mesh.vertices.size(); ++i) {
    const Eigen::Vector3f& v = mesh.vertices[i];
    if (!v.allFinite()) throw MeshError("mesh '" + path + "': non-finite vertex");
    if (v.cwiseAbs().maxCoeff() > mesh_check::kMaxCoordinate) {
      std::ostringstream at;
      at << "mesh '" << path << "': vertex " << i << " at (" << v.x() << ", " << v.y() << ", " << v.z()
         << ") is out of range: farther than " << mesh_check::kMaxCoordinate
         << " m from the mesh origin (unit, nodes and scale applied)";
      throw MeshError(at.str());
    }
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
  if (m->texture_uri.rfind(kNoImage, 0) == 0) {
    m->texture_error = "image '" + m->texture_uri.substr(std::strlen(kNoImage)) +
                       "' names no file (Gazebo draws the colour too)";
    return;
  }
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

// Appends the triangles of the instances with UVs and material indices; vertices are joined
// by exact position.
void collectWithMaterials(const std::vector<Instance>& parts, const aiVector3D& offset,
                          const Eigen::Vector3d& scale,
                          std::map<std::array<float, 3>, uint32_t>* joined, bool* any_uv,
                          TriangleMesh* out) {
  for (const Instance& in : parts) {
    const aiMesh* mesh = in.mesh;
    std::vector<uint32_t> index(mesh->mNumVertices);
    for (unsigned v = 0; v < mesh->mNumVertices; ++v) {
      const std::array<float, 3> key = place(in, v, offset, scale);
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
}

// A COLLADA file whose <image>s without a file (an <init_from> commented out, as in several
// gazebo_models parts) each get a placeholder file name, so that assimp, which refuses such an
// image ("Invalid texture, no data or file reference given"), reads the geometry, as Gazebo's
// ColladaLoader does (it just draws the material's colour). "" when there is nothing to mend.
// Skins, morphs and animations are left out of what assimp reads: the loader keeps no bones
// and no animation, and assimp 5.2 trusts their indices (ColladaLoader::CreateMesh indexes its
// bones with the <v> joint indices and reads weights with an ai_assert: SIGSEGV and SIGABRT on
// a mutated <vertex_weights>; ColladaParser::ReadControllerWeights sizes its arrays by `count`
// and the <vcount> sum). A node's <instance_controller> becomes an <instance_geometry> of the
// skin's or morph's source mesh, with its <bind_material>: assimp places a skinned mesh's
// vertices exactly so (the bind shape matrix only goes into the bones' offset matrices), and
// Gazebo's ColladaLoader.cc LoadController also loads the skin's source geometry at the node.
// Returns the number of changes.
int withoutControllersAndAnimations(tinyxml2::XMLDocument& doc) {
  std::map<std::string, std::string> source_of;  // controller id -> its mesh's id
  std::vector<tinyxml2::XMLElement*> remove, instances;
  std::vector<tinyxml2::XMLElement*> stack;
  if (doc.RootElement()) stack.push_back(doc.RootElement());
  while (!stack.empty()) {
    tinyxml2::XMLElement* e = stack.back();
    stack.pop_back();
    const std::string name = e->Name();
    if (name == "controller") {
      const char* id = e->Attribute("id");
      for (const char* kind : {"skin", "morph"}) {
        const tinyxml2::XMLElement* k = e->FirstChildElement(kind);
        const char* src = k ? k->Attribute("source") : nullptr;
        if (id && src && src[0] == '#') source_of[id] = src + 1;
      }
    } else if (name == "instance_controller") {
      instances.push_back(e);
    }
    if (name == "library_controllers" || name == "library_animations" || name == "library_animation_clips") {
      remove.push_back(e);
    }
    for (tinyxml2::XMLElement* c = e->FirstChildElement(); c; c = c->NextSiblingElement()) stack.push_back(c);
  }
  for (tinyxml2::XMLElement* inst : instances) {
    const char* url = inst->Attribute("url");
    const auto it = url && url[0] == '#' ? source_of.find(url + 1) : source_of.end();
    if (it == source_of.end()) {
      remove.push_back(inst);  // assimp would find no mesh for it either
      continue;
    }
    inst->SetName("instance_geometry");
    inst->SetAttribute("url", ("#" + it->second).c_str());
    while (tinyxml2::XMLElement* skeleton = inst->FirstChildElement("skeleton")) inst->DeleteChild(skeleton);
  }
  // Parents before children in `remove` (pre-order): delete the deepest first.
  for (auto it = remove.rbegin(); it != remove.rend(); ++it) {
    if (tinyxml2::XMLNode* parent = (*it)->Parent()) parent->DeleteChild(*it);
  }
  return static_cast<int>(remove.size() + instances.size());
}

std::string colladaWithImagePlaceholders(tinyxml2::XMLDocument& doc) {
  tinyxml2::XMLElement* root = doc.RootElement();
  int mended = 0;
  for (tinyxml2::XMLElement* lib = root ? root->FirstChildElement("library_images") : nullptr; lib;
       lib = lib->NextSiblingElement("library_images")) {
    for (tinyxml2::XMLElement* image = lib->FirstChildElement("image"); image;
         image = image->NextSiblingElement("image")) {
      if (image->FirstChildElement("init_from") || image->FirstChildElement("data")) continue;
      const char* id = image->Attribute("id");
      tinyxml2::XMLElement* init = doc.NewElement("init_from");
      init->SetText((kNoImage + std::string(id ? id : "")).c_str());
      image->InsertEndChild(init);
      ++mended;
    }
  }
  mended += withoutControllersAndAnimations(doc);
  if (mended == 0) return "";
  tinyxml2::XMLPrinter printer;
  doc.Print(&printer);
  return printer.CStr();
}

// Reads the file with the settings that give Gazebo's placement (see the rules above).
const aiScene* readScene(Assimp::Importer* importer, const std::string& path, unsigned removed) {
  importer->SetPropertyInteger(AI_CONFIG_PP_SBP_REMOVE, aiPrimitiveType_POINT | aiPrimitiveType_LINE);
  importer->SetPropertyInteger(AI_CONFIG_PP_RVC_FLAGS, static_cast<int>(removed));
  importer->SetPropertyBool(AI_CONFIG_IMPORT_COLLADA_IGNORE_UP_DIRECTION, true);
  // Node names as the file writes them (<node name>, not its id): Gazebo's submesh names.
  importer->SetPropertyBool(AI_CONFIG_IMPORT_COLLADA_USE_COLLADA_NAMES, true);
  // A file without geometry is an error, not assimp's stand-in (a zero-size "skeleton" mesh
  // at each node, which would collide and be seen as a point).
  importer->SetPropertyBool(AI_CONFIG_IMPORT_NO_SKELETON_MESHES, true);
  importer->SetIOHandler(new RegularFilesOnly);  // the importer owns it
  // What assimp 5.2 trusts in a COLLADA file is checked first (mesh_check.h); STL needs no
  // pre-pass: assimp checks a binary file's facet count against its size (STLLoader.cpp
  // LoadBinaryFile), and an ASCII file's facets are bounded by its size; OBJ indices are
  // checked by assimp (ObjFileImporter) and by checkScene.
  // ValidateDataStructure: assimp's own check of its scene, before the other steps read it.
  const unsigned flags = aiProcess_ValidateDataStructure | aiProcess_RemoveComponent | aiProcess_Triangulate |
                         aiProcess_JoinIdenticalVertices | aiProcess_SortByPType;
  std::string mended;
  if (mesh_check::looksLikeCollada(path)) {
    tinyxml2::XMLDocument doc;
    mesh_check::checkCollada(path, &doc);
    // Mended before assimp sees it rather than after it refused the file: assimp leaks what it
    // had built when it throws "Invalid texture" (found by fuzz_mesh's LeakSanitizer). Skins
    // and animations go too (withoutControllersAndAnimations).
    mended = colladaWithImagePlaceholders(doc);
  }
  const aiScene* scene = mended.empty() ? importer->ReadFile(path, flags)
                                        : importer->ReadFileFromMemory(mended.data(), mended.size(), flags, "dae");
  if (scene == nullptr || scene->mRootNode == nullptr) importFailed(path, *importer);
  mesh_check::checkScene(path, scene);
  return scene;
}

}  // namespace

TriangleMesh loadMesh(const MeshSource& source) {
  checkFile(source.path, source.scale);
  Assimp::Importer importer;
  // Only positions are kept: dropping STL's per-facet normals (and UVs, colours) first lets
  // JoinIdenticalVertices merge the corners that facets share.
  const aiScene* scene =
      readScene(&importer, source.path,
                aiComponent_NORMALS | aiComponent_TANGENTS_AND_BITANGENTS | aiComponent_COLORS |
                    aiComponent_TEXCOORDS | aiComponent_BONEWEIGHTS | aiComponent_ANIMATIONS |
                    aiComponent_TEXTURES | aiComponent_LIGHTS | aiComponent_CAMERAS |
                    aiComponent_MATERIALS);
  aiVector3D offset;
  const std::vector<Instance> parts = select(scene, source, &offset);
  TriangleMesh mesh;
  collect(parts, offset, source.scale, &mesh);
  checkResult(source.path, mesh);
  return mesh;
}

TriangleMesh loadMeshFile(const std::string& path, const Eigen::Vector3d& scale) {
  return loadMesh(MeshSource{path, scale, "", false});
}

TriangleMesh loadMeshWithMaterials(const MeshSource& source) {
  const std::string& path = source.path;
  checkFile(path, source.scale);
  Assimp::Importer importer;
  const aiScene* scene =
      readScene(&importer, path,
                aiComponent_NORMALS | aiComponent_TANGENTS_AND_BITANGENTS | aiComponent_COLORS |
                    aiComponent_BONEWEIGHTS | aiComponent_ANIMATIONS | aiComponent_LIGHTS |
                    aiComponent_CAMERAS);
  aiVector3D offset;
  const std::vector<Instance> parts = select(scene, source, &offset);
  TriangleMesh mesh;
  std::map<std::array<float, 3>, uint32_t> joined;
  bool any_uv = false;
  collectWithMaterials(parts, offset, source.scale, &joined, &any_uv, &mesh);
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

TriangleMesh loadMeshFileWithMaterials(const std::string& path, const Eigen::Vector3d& scale) {
  return loadMeshWithMaterials(MeshSource{path, scale, "", false});
}

namespace {

MeshSource sourceOf(const std::string& path, const Eigen::Vector3d& scale) {
  MeshSource source;
  source.path = path;
  source.scale = scale;
  return source;
}

}  // namespace

std::shared_ptr<const TriangleMesh> MeshCache::get(const MeshSource& source) {
  return find(source, false);
}

std::shared_ptr<const TriangleMesh> MeshCache::get(const std::string& path,
                                                   const Eigen::Vector3d& scale) {
  return find(sourceOf(path, scale), false);
}

std::shared_ptr<const TriangleMesh> MeshCache::getWithMaterials(const MeshSource& source) {
  return find(source, true);
}

std::shared_ptr<const TriangleMesh> MeshCache::getWithMaterials(const std::string& path,
                                                                const Eigen::Vector3d& scale) {
  return find(sourceOf(path, scale), true);
}

std::shared_ptr<const TriangleMesh> MeshCache::find(const MeshSource& source, bool materials) {
  const Key key{source.path,    source.scale.x(),       source.scale.y(), source.scale.z(),
                source.submesh, source.center_submesh, materials};
  {
    std::lock_guard<std::mutex> lock(mutex_);
    auto it = meshes_.find(key);
    if (it != meshes_.end()) return it->second;
  }
  // Parse outside the lock; if two threads race, the first insert wins (same content).
  auto mesh = std::make_shared<const TriangleMesh>(materials ? loadMeshWithMaterials(source)
                                                             : loadMesh(source));
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
