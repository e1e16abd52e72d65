// Checks of a mesh file before assimp reads it, and of what assimp returns before it is used
// (issue 43: malformed COLLADA made assimp abort, read out of bounds or allocate without bound).
// Internal to tianracer_assets_mesh; mesh.cpp calls them. ROS-free.
#ifndef TIANRACER_ASSETS_MESH_CHECK_H
#define TIANRACER_ASSETS_MESH_CHECK_H

#include <cstdint>
#include <string>

#include "tianracer_assets/file_kind.h"

struct aiScene;
namespace tinyxml2 {
class XMLDocument;
}

namespace tianracer_assets {
namespace mesh_check {

using tianracer_assets::fileProblem;

// Limits well above any real model (the largest gazebo_models mesh has about 1e5 triangles; a
// 1e7-triangle mesh already takes gigabytes in assimp), so that a file that would make assimp
// allocate without bound is an error first.
constexpr std::uint64_t kMaxFileBytes = 256ull << 20;  // 256 MiB
constexpr std::uint64_t kMaxTriangles = 10000000;      // placed triangles, instances counted
constexpr std::uint64_t kMaxVertices = 10000000;       // vertices assimp creates
constexpr std::uint64_t kMaxNodes = 1000000;           // COLLADA nodes, instances expanded
constexpr int kMaxNodeDepth = 1000;                     // COLLADA node nesting, instances followed
// A placed vertex farther than this from the mesh origin (after unit, nodes and scale) is an
// error: the world's positions are held to the same bound (1e6 m), and Embree and Bullet lose
// all precision far beyond it.
constexpr double kMaxCoordinate = 1e6;

/// True when the file is COLLADA: a .dae name, or "<COLLADA" near its start (assimp picks its
/// importer by the extension, else by such a signature).
bool looksLikeCollada(const std::string& path);

/// The pre-pass over a COLLADA file (tinyxml2) that checks what assimp 5.2's ColladaParser
/// trusts: accessor counts, strides and offsets against their arrays, <p> and <vcount> lists,
/// input offsets, node cycles, and the size limits above. Throws MeshError
/// "<path>:<line>: COLLADA <element ...>: <what is wrong>". `doc` receives the parsed file
/// (the loader mends its images without parsing it again).
void checkCollada(const std::string& path, tinyxml2::XMLDocument* doc);

/// The scene assimp returned, before anything reads it: node tree (depth, mesh indices), faces
/// (sizes, vertex indices in range), vertex arrays, and the placed-triangle limit. Throws
/// MeshError naming the path.
void checkScene(const std::string& path, const aiScene* scene);

}  // namespace mesh_check
}  // namespace tianracer_assets

#endif  // TIANRACER_ASSETS_MESH_CHECK_H
