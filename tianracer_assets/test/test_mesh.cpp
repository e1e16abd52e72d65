// mesh_loader: assimp into plain triangle lists, the cache, and the error texts.
#include <gtest/gtest.h>

#include <cstdio>
#include <fstream>
#include <string>

#include "tianracer_assets/mesh.h"

namespace tianracer_assets {
namespace {

const std::string kWheel = std::string(TIANRACER_DESCRIPTION_DIR) + "/meshes/left_rear_wheel.STL";

std::string writeTemp(const std::string& name, const std::string& content) {
  const std::string path = ::testing::TempDir() + "/" + name;
  std::ofstream(path) << content;
  return path;
}

// A 10 cm cube centred on the origin as an ASCII STL: 12 facets, each repeating its corners.
std::string cubeStl() {
  const int quads[6][4][3] = {{{0, 0, 0}, {0, 1, 0}, {1, 1, 0}, {1, 0, 0}}, {{0, 0, 1}, {1, 0, 1}, {1, 1, 1}, {0, 1, 1}},
                              {{0, 0, 0}, {1, 0, 0}, {1, 0, 1}, {0, 0, 1}}, {{0, 1, 0}, {0, 1, 1}, {1, 1, 1}, {1, 1, 0}},
                              {{0, 0, 0}, {0, 0, 1}, {0, 1, 1}, {0, 1, 0}}, {{1, 0, 0}, {1, 1, 0}, {1, 1, 1}, {1, 0, 1}}};
  std::string s = "solid cube\n";
  auto corner = [](const int* c) {
    std::string v = "vertex";
    for (int k = 0; k < 3; ++k) v += c[k] ? " 0.05" : " -0.05";
    return v + "\n";
  };
  for (const auto& q : quads) {
    s += "facet normal 0 0 0\nouter loop\n" + corner(q[0]) + corner(q[1]) + corner(q[2]) + "endloop\nendfacet\n";
    s += "facet normal 0 0 0\nouter loop\n" + corner(q[0]) + corner(q[2]) + corner(q[3]) + "endloop\nendfacet\n";
  }
  return s + "endsolid cube\n";
}

const std::string kCube = writeTemp("cube_10cm.stl", cubeStl());

std::string errorOf(const std::string& path) {
  try {
    loadMeshFile(path);
  } catch (const MeshError& e) {
    return e.what();
  }
  return "";
}

// Loading the file `name` written with `content` fails with an error that names its path and,
// when given, says `why`.
void expectErrorNamesTheFile(const std::string& name, const std::string& content,
                             const char* why = nullptr) {
  const std::string path = writeTemp(name, content);
  const std::string e = errorOf(path);
  EXPECT_NE(e.find(path), std::string::npos) << e;
  if (why) {
    EXPECT_NE(e.find(why), std::string::npos) << e;
  }
}

TEST(MeshLoader, CubeIsTwelveTrianglesOnEightJoinedVertices) {
  const TriangleMesh m = loadMeshFile(kCube);
  EXPECT_EQ(m.triangleCount(), 12u);
  EXPECT_EQ(m.vertices.size(), 8u);  // STL repeats corners per facet; joined here
  EXPECT_TRUE(m.boundsMin().isApprox(Eigen::Vector3f::Constant(-0.05f)));
  EXPECT_TRUE(m.boundsMax().isApprox(Eigen::Vector3f::Constant(0.05f)));
  for (uint32_t i : m.indices) EXPECT_LT(i, m.vertices.size());
}

TEST(MeshLoader, ScaleIsAppliedPerAxis) {
  const TriangleMesh m = loadMeshFile(kCube, Eigen::Vector3d(2.0, 1.0, 0.5));
  EXPECT_TRUE(m.boundsMax().isApprox(Eigen::Vector3f(0.1f, 0.05f, 0.025f)));
}

TEST(MeshLoader, GeneratedWheelHasTheSeedRadiusAndWidth) {
  const TriangleMesh m = loadMeshFile(kWheel);
  EXPECT_NEAR(m.boundsMax().x(), 0.032, 1e-6);
  EXPECT_NEAR(m.boundsMax().y() - m.boundsMin().y(), 0.025, 1e-6);
}

TEST(MeshCache, LoadsEachPathAndScaleOnce) {
  MeshCache cache;
  auto a = cache.get(kCube);
  auto b = cache.get(kCube);
  EXPECT_EQ(a.get(), b.get());
  EXPECT_EQ(cache.size(), 1u);
  auto c = cache.get(kCube, Eigen::Vector3d(2, 2, 2));
  EXPECT_NE(a.get(), c.get());
  EXPECT_EQ(cache.size(), 2u);
  cache.clear();
  EXPECT_EQ(cache.size(), 0u);
  EXPECT_EQ(a->triangleCount(), 12u);  // callers keep their meshes after clear()
}

TEST(MeshCache, ErrorsAreNotCached) {
  MeshCache cache;
  EXPECT_THROW(cache.get("/nonexistent/mesh.stl"), MeshError);
  EXPECT_EQ(cache.size(), 0u);
}

TEST(MeshLoader, MissingFileNamesThePath) {
  const std::string e = errorOf("/nonexistent/dir/wheel.STL");
  EXPECT_NE(e.find("/nonexistent/dir/wheel.STL"), std::string::npos) << e;
  EXPECT_NE(e.find("not found"), std::string::npos) << e;
}

TEST(MeshLoader, EmptyFileNamesThePath) { expectErrorNamesTheFile("empty.stl", "", "empty"); }

TEST(MeshLoader, GarbageIsUnreadable) {
  expectErrorNamesTheFile("garbage.dae", "this is not a mesh at all");
}

TEST(MeshLoader, NoTrianglesIsAnError) {
  // A valid OBJ with vertices and a single line element only.
  expectErrorNamesTheFile("lines.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nl 1 2\n", "': no triangles");
}

TEST(MeshLoader, DirectoryIsNotAMesh) {
  const std::string e = errorOf(::testing::TempDir());
  EXPECT_NE(e.find("is a directory, not a mesh file"), std::string::npos) << e;
}

}  // namespace
}  // namespace tianracer_assets
