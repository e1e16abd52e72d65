// Meshes as Gazebo classic places them (docs/meshes.md), one hand-written file per rule in
// test/data/meshes: the bounds each mesh Shape gets through meshOf, the one function physics,
// the ray caster and the renderer take meshes from.
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <string>
#include <vector>

#include "tianracer_sim/mesh/mesh_loader.h"

#include "common_test_support.h"

namespace tianracer_sim {
namespace {

using ::testing::HasSubstr;

const std::string kMeshes = std::string(TEST_DATA_DIR) + "/meshes/";

Shape meshShape(const std::string& file, const Eigen::Vector3d& scale = Eigen::Vector3d::Ones(),
                const std::string& submesh = "", bool center = false) {
  Shape s;
  s.type = ShapeType::kMesh;
  s.mesh_path = kMeshes + file;
  s.scale = scale;
  s.submesh = submesh;
  s.center_submesh = center;
  return s;
}

void expectBounds(const TriangleMesh& m, const Eigen::Vector3f& lo, const Eigen::Vector3f& hi) {
  EXPECT_TRUE(m.boundsMin().isApprox(lo, 1e-5f)) << "min " << m.boundsMin().transpose() << ", expected "
                                                  << lo.transpose();
  EXPECT_TRUE(m.boundsMax().isApprox(hi, 1e-5f)) << "max " << m.boundsMax().transpose() << ", expected "
                                                  << hi.transpose();
}

std::string errorOf(const Shape& s) {
  return test::errorText<MeshError>([&] { meshOf(s); });
}

TEST(MeshRules, ColladaUnitAndNestedNodeTransformsApplyAndZUpStaysUp) {
  // Box x -1..1, y -2..2, z 0..3 in; inner node Rz(90) and +1 x, outer node <matrix> x2 and
  // +(10, 0, 5): x 8..16, y -2..2, z 5..11 in. assimp's default would turn Z_UP into Y_UP
  // (z 5..11 in along y); Gazebo does not, nor do we.
  const auto m = meshOf(meshShape("collada_inch_zup_nodes.dae"));
  expectBounds(*m, Eigen::Vector3f(0.2032f, -0.0508f, 0.127f), Eigen::Vector3f(0.4064f, 0.0508f, 0.2794f));
  EXPECT_EQ(m->triangleCount(), 12u);
}

TEST(MeshRules, ColladaYUpIsNotRotatedEither) {
  expectBounds(*meshOf(meshShape("collada_yup.dae")), Eigen::Vector3f(-1, -2, 0), Eigen::Vector3f(1, 2, 3));
}

TEST(MeshRules, ColladaGeometryInstancedTwiceIsPlacedAtBothNodes) {
  const auto m = meshOf(meshShape("collada_instanced.dae"));
  EXPECT_EQ(m->triangleCount(), 24u);
  expectBounds(*m, Eigen::Vector3f(-2.5f, -0.5f, -0.5f), Eigen::Vector3f(2.5f, 0.5f, 1.0f));
}

TEST(MeshRules, StlAsciiAndBinaryWithASolidHeaderAreTheSameTetrahedron) {
  const auto ascii = meshOf(meshShape("stl_ascii.stl"));
  const auto binary = meshOf(meshShape("stl_binary_solid_header.stl"));
  for (const auto& m : {ascii, binary}) {
    EXPECT_EQ(m->triangleCount(), 4u);
    EXPECT_EQ(m->vertices.size(), 4u);  // facets' shared corners joined
    expectBounds(*m, Eigen::Vector3f(0, 0, 0), Eigen::Vector3f(1, 2, 3));
  }
}

TEST(MeshRules, ObjGroupsKeepTheirMtlColours) {
  const auto m = meshWithMaterialsOf(meshShape("obj_groups.obj"));
  expectBounds(*m, Eigen::Vector3f(0, 0, 0), Eigen::Vector3f(3, 1, 1));
  ASSERT_EQ(m->triangleCount(), 24u);
  // Each triangle's material is its group's: red for x <= 1, blue for x >= 2.
  int red = 0, blue = 0;
  for (std::size_t t = 0; t < m->triangleCount(); ++t) {
    const MeshMaterial& mm = m->materials.at(m->triangle_material.at(t));
    const float x = m->vertices[m->indices[3 * t]].x();
    ASSERT_TRUE(mm.has_diffuse) << mm.name;
    if (mm.name == "red") {
      ++red;
      EXPECT_LE(x, 1.0f);
      EXPECT_TRUE(mm.diffuse.head<3>().isApprox(Eigen::Vector3f(1, 0, 0)));
    } else {
      ++blue;
      EXPECT_EQ(mm.name, "blue");
      EXPECT_GE(x, 2.0f);
      EXPECT_TRUE(mm.diffuse.head<3>().isApprox(Eigen::Vector3f(0, 0, 1)));
    }
  }
  EXPECT_EQ(red, 12);
  EXPECT_EQ(blue, 12);
}

TEST(MeshRules, SdfScaleAppliesAfterTheFilesUnitAndNodes) {
  // The construction cone's pattern: inches in the file, <scale>10 10 10</scale> in the SDF.
  expectBounds(*meshOf(meshShape("collada_inch_zup_nodes.dae", Eigen::Vector3d(10, 10, 10))),
               Eigen::Vector3f(2.032f, -0.508f, 1.27f), Eigen::Vector3f(4.064f, 0.508f, 2.794f));
  expectBounds(*meshOf(meshShape("stl_ascii.stl", Eigen::Vector3d(2, 1, 0.5))), Eigen::Vector3f(0, 0, 0),
               Eigen::Vector3f(2, 2, 1.5));
}

TEST(MeshRules, SubmeshSelectsANodeByNameWithItsUnnamedChildren) {
  const auto left = meshOf(meshShape("collada_submeshes.dae", Eigen::Vector3d::Ones(), "left"));
  EXPECT_EQ(left->triangleCount(), 12u);
  expectBounds(*left, Eigen::Vector3f(1, -0.5f, 0.5f), Eigen::Vector3f(2, 0.5f, 1.5f));
  // right's geometry sits in a child node without a name: still part 'right' (Gazebo's rule).
  const auto right = meshOf(meshShape("collada_submeshes.dae", Eigen::Vector3d::Ones(), "right"));
  expectBounds(*right, Eigen::Vector3f(-4, -1, -1), Eigen::Vector3f(-2, 1, 1));
  // The whole file holds both.
  expectBounds(*meshOf(meshShape("collada_submeshes.dae")), Eigen::Vector3f(-4, -1, -1),
               Eigen::Vector3f(2, 1, 1.5f));
}

TEST(MeshRules, CenteredSubmeshIsCentredBeforeTheScale) {
  expectBounds(*meshOf(meshShape("collada_submeshes.dae", Eigen::Vector3d::Ones(), "left", true)),
               Eigen::Vector3f(-0.5f, -0.5f, -0.5f), Eigen::Vector3f(0.5f, 0.5f, 0.5f));
  expectBounds(*meshOf(meshShape("collada_submeshes.dae", Eigen::Vector3d(3, 1, 1), "right", true)),
               Eigen::Vector3f(-3, -1, -1), Eigen::Vector3f(3, 1, 1));
  // <center> without a <submesh> name changes nothing (Gazebo reads it inside <submesh> only).
  expectBounds(*meshOf(meshShape("collada_submeshes.dae", Eigen::Vector3d::Ones(), "", true)),
               Eigen::Vector3f(-4, -1, -1), Eigen::Vector3f(2, 1, 1.5f));
}

TEST(MeshRules, ColladaImageWithoutAFileLosesItsTextureOnly) {
  expectBounds(*meshOf(meshShape("collada_image_without_file.dae")), Eigen::Vector3f(-1, -2, 0),
               Eigen::Vector3f(1, 2, 3));
  const auto m = meshWithMaterialsOf(meshShape("collada_image_without_file.dae"));
  EXPECT_EQ(m->triangleCount(), 12u);
  bool painted = false;
  for (const MeshMaterial& mm : m->materials) {
    if (mm.name != "paint") continue;
    painted = true;
    EXPECT_TRUE(mm.texture.empty());
    EXPECT_THAT(mm.texture_error, HasSubstr("image 'paint_png' names no file"));
  }
  EXPECT_TRUE(painted);
}

TEST(MeshRules, ObjGroupIsASubmesh) {
  expectBounds(*meshOf(meshShape("obj_groups.obj", Eigen::Vector3d::Ones(), "blue_block", true)),
               Eigen::Vector3f(-0.5f, -0.5f, -0.5f), Eigen::Vector3f(0.5f, 0.5f, 0.5f));
}

TEST(MeshRules, CollisionAndCamerasPlaceEveryRuleFileAlike) {
  // Physics and the ray caster take meshOf, the renderer meshWithMaterialsOf (UVs and
  // materials): the same vertices, whatever the rule.
  const std::vector<Shape> shapes = {
      meshShape("collada_inch_zup_nodes.dae", Eigen::Vector3d(10, 10, 10)),
      meshShape("collada_yup.dae"),
      meshShape("collada_instanced.dae"),
      meshShape("collada_submeshes.dae", Eigen::Vector3d(2, 1, 1), "right", true),
      meshShape("collada_image_without_file.dae"),
      meshShape("stl_binary_solid_header.stl", Eigen::Vector3d(1, 2, 3)),
      meshShape("obj_groups.obj", Eigen::Vector3d::Ones(), "red_block")};
  for (const Shape& s : shapes) {
    const auto collision = meshOf(s);
    const auto visual = meshWithMaterialsOf(s);
    EXPECT_EQ(collision->triangleCount(), visual->triangleCount()) << s.mesh_path;
    EXPECT_EQ(collision->boundsMin(), visual->boundsMin()) << s.mesh_path;
    EXPECT_EQ(collision->boundsMax(), visual->boundsMax()) << s.mesh_path;
  }
}

TEST(MeshRules, UnknownSubmeshNamesTheFileAndItsParts) {
  const std::string e = errorOf(meshShape("collada_submeshes.dae", Eigen::Vector3d::Ones(), "middle"));
  EXPECT_THAT(e, HasSubstr("collada_submeshes.dae': no submesh 'middle' (its parts: 'left', 'right')"));
}

TEST(MeshRules, ColladaWithoutGeometryIsAnErrorNamingTheFile) {
  const std::string e = errorOf(meshShape("collada_no_geometry.dae"));
  EXPECT_THAT(e, HasSubstr("collada_no_geometry.dae': no triangles"));
}

TEST(MeshRules, UnreadableFileIsAnErrorNamingTheFile) {
  const std::string e = errorOf(meshShape("unreadable.dae"));
  EXPECT_THAT(e, HasSubstr("unreadable.dae': unreadable"));
}

TEST(MeshRules, ZeroOrNegativeScaleIsAnErrorNamingTheFile) {
  EXPECT_THAT(errorOf(meshShape("stl_ascii.stl", Eigen::Vector3d(1, 0, 1))),
              HasSubstr("stl_ascii.stl': scale must be finite and positive"));
  EXPECT_THAT(errorOf(meshShape("stl_ascii.stl", Eigen::Vector3d(1, 1, -1))),
              HasSubstr("scale must be finite and positive"));
}

}  // namespace
}  // namespace tianracer_sim

int main(int argc, char** argv) {
  ::testing::InitGoogleTest(&argc, argv);  // gtest only: gmock matchers are header-only
  return RUN_ALL_TESTS();
}
