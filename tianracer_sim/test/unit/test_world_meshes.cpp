// SDF <mesh> in worlds: <uri>, <scale> and <submesh> into the Shape every consumer places
// (mesh/mesh_loader.h).
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <string>
#include <vector>

#include "tianracer_sim/world/world.h"

namespace tianracer_sim {
namespace {

using ::testing::HasSubstr;

const std::string kData = std::string(TEST_DATA_DIR) + "/";

std::string worldWith(const std::string& models) {
  return "<sdf version='1.6'><world name='w'>" + models + "</world></sdf>";
}

std::string meshModel(const std::string& name, const std::string& mesh_xml) {
  return "<model name='" + name + "'><static>true</static><link name='l'><collision name='c'>"
         "<geometry><mesh>" + mesh_xml + "</mesh></geometry></collision></link></model>";
}

TEST(WorldMeshes, SubmeshNameAndCenterAndScaleReachTheShape) {
  const WorldDescription w = loadWorldString(
      worldWith(meshModel("m", "<uri>meshes/collada_submeshes.dae</uri><scale>2 3 4</scale>"
                                "<submesh><name>left</name><center>true</center></submesh>")),
      "test.world", kData);
  const Shape& s = w.models.at(0).links.at(0).collisions.at(0).shape;
  EXPECT_EQ(s.mesh_path, kData + "meshes/collada_submeshes.dae");
  EXPECT_EQ(s.scale, Eigen::Vector3d(2, 3, 4));
  EXPECT_EQ(s.submesh, "left");
  EXPECT_TRUE(s.center_submesh);
}

TEST(WorldMeshes, SubmeshWithoutCenterIsNotCentred) {
  const WorldDescription w = loadWorldString(
      worldWith(meshModel("m", "<uri>meshes/collada_submeshes.dae</uri>"
                                "<submesh><name>right</name></submesh>")),
      "test.world", kData);
  const Shape& s = w.models.at(0).links.at(0).collisions.at(0).shape;
  EXPECT_EQ(s.submesh, "right");
  EXPECT_FALSE(s.center_submesh);
}

}  // namespace
}  // namespace tianracer_sim

int main(int argc, char** argv) {
  ::testing::InitGoogleTest(&argc, argv);  // gtest only: gmock matchers are header-only
  return RUN_ALL_TESTS();
}
