// SDF <mesh> in worlds: <uri>, <scale> and <submesh> into the Shape every consumer places
// (mesh/mesh_loader.h), and what a mesh that cannot be used does to the rest of the world.
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <string>
#include <vector>

#include "tianracer_sim/world/world.h"

#include "common_test_support.h"

namespace tianracer_sim {
namespace {

using ::testing::HasSubstr;
using ::testing::Not;

const std::string kData = std::string(TEST_DATA_DIR) + "/";

std::string worldWith(const std::string& models) {
  return "<sdf version='1.6'><world name='w'>" + models + "</world></sdf>";
}

std::string meshModel(const std::string& name, const std::string& mesh_xml) {
  return "<model name='" + name + "'><static>true</static><link name='l'><collision name='c'>"
         "<geometry><mesh>" + mesh_xml + "</mesh></geometry></collision></link></model>";
}

// The Shape of a world whose one model has the <mesh> `mesh_xml` as its collision.
Shape meshShape(const std::string& mesh_xml) {
  const WorldDescription w =
      loadWorldString(worldWith(meshModel("m", mesh_xml)), "test.world", kData);
  return w.models.at(0).links.at(0).collisions.at(0).shape;
}

TEST(WorldMeshes, SubmeshNameAndCenterAndScaleReachTheShape) {
  const Shape s = meshShape("<uri>meshes/collada_submeshes.dae</uri><scale>2 3 4</scale>"
                            "<submesh><name>left</name><center>true</center></submesh>");
  EXPECT_EQ(s.mesh_path, kData + "meshes/collada_submeshes.dae");
  EXPECT_EQ(s.scale, Eigen::Vector3d(2, 3, 4));
  EXPECT_EQ(s.submesh, "left");
  EXPECT_TRUE(s.center_submesh);
}

TEST(WorldMeshes, SubmeshWithoutCenterIsNotCentred) {
  const Shape s =
      meshShape("<uri>meshes/collada_submeshes.dae</uri><submesh><name>right</name></submesh>");
  EXPECT_EQ(s.submesh, "right");
  EXPECT_FALSE(s.center_submesh);
}

// Bad or missing content (Gazebo logs an error and loads the rest): each case leaves out one
// geometry or model with an error naming file, line, what and why; the rest of the world loads.
struct Loaded {
  WorldDescription world;
  std::vector<std::string> errors, warnings;
};

Loaded load(const std::string& models, bool strict = false) {
  Loaded out;
  WorldLoadOptions o;
  o.model_paths = {kData + "worlds/models"};
  o.error = [&](const std::string& e) { out.errors.push_back(e); };
  o.warn = [&](const std::string& w) { out.warnings.push_back(w); };
  o.strict = strict;
  out.world = loadWorldString(worldWith(models + meshModel("good", "<uri>meshes/stl_ascii.stl</uri>")),
                              "test.world", kData, o);
  return out;
}

std::string strictError(const std::string& models) {
  return test::errorText<WorldError>([&] { load(models, true); });
}

const ModelDescription* model(const WorldDescription& w, const std::string& name) {
  for (const ModelDescription& m : w.models)
    if (m.name == name) return &m;
  return nullptr;
}

TEST(WorldMeshes, MissingIncludeIsAnErrorNamingTheUriAndFoldersAndTheRestLoads) {
  const Loaded l = load("<include><uri>model://no_such_model</uri></include>");
  ASSERT_EQ(l.errors.size(), 1u);
  EXPECT_THAT(l.errors[0], HasSubstr("test.world:1: <include> of 'model://no_such_model': model not "
                                     "found; searched: "));
  EXPECT_THAT(l.errors[0], HasSubstr(kData + "worlds/models"));
  EXPECT_THAT(l.errors[0], HasSubstr("; the model is left out"));
  ASSERT_EQ(l.world.models.size(), 1u);
  EXPECT_EQ(l.world.models[0].name, "good");
  EXPECT_EQ(l.world.models[0].links[0].collisions.size(), 1u);
  // ~strict_world: the same message stops the load.
  const std::string e = strictError("<include><uri>model://no_such_model</uri></include>");
  EXPECT_THAT(e, HasSubstr("<include> of 'model://no_such_model': model not found; searched: "));
  EXPECT_THAT(e, Not(HasSubstr("left out")));
}

TEST(WorldMeshes, MissingNestedIncludeLeavesOutThatPartOnly) {
  const Loaded l = load("<model name='outer'><static>true</static><link name='base'/>"
                        "<include><uri>model://gone</uri></include></model>");
  ASSERT_EQ(l.errors.size(), 1u);
  EXPECT_THAT(l.errors[0], HasSubstr("<include> of 'model://gone': model not found"));
  ASSERT_NE(model(l.world, "outer"), nullptr);
  EXPECT_EQ(model(l.world, "outer")->links.size(), 1u);
  EXPECT_NE(model(l.world, "good"), nullptr);
}

TEST(WorldMeshes, JointsToALeftOutIncludeGoWithIt) {
  const Loaded l = load("<model name='outer'><link name='base'/>"
                        "<include><uri>model://gone</uri><name>gone</name></include>"
                        "<joint name='mount' type='fixed'><parent>base</parent><child>gone::link</child>"
                        "</joint></model>");
  ASSERT_EQ(l.errors.size(), 2u);
  EXPECT_THAT(l.errors[1], HasSubstr("model 'outer' joint 'mount': no link 'gone::link' in the model "
                                     "(an <include> of it was left out); the joint is left out"));
  ASSERT_NE(model(l.world, "outer"), nullptr);
  EXPECT_TRUE(model(l.world, "outer")->joints.empty());
  // Without a left-out include, a joint to a link the model lacks is left out with an error
  // naming the model's links; ~strict_world stops.
  const std::string bad_joint = "<model name='outer'><link name='base'/><joint name='j' type='fixed'>"
                                "<parent>base</parent><child>nope</child></joint></model>";
  const Loaded alone = load(bad_joint);
  ASSERT_EQ(alone.errors.size(), 1u);
  EXPECT_THAT(alone.errors[0], HasSubstr("model 'outer' joint 'j': no link 'nope' in the model "
                                         "(links: base); the joint is left out"));
  EXPECT_TRUE(model(alone.world, "outer")->joints.empty());
  EXPECT_THROW(load(bad_joint, true), WorldError);
}

TEST(WorldMeshes, MissingMeshLeavesOutThatCollisionOnly) {
  const Loaded l = load(
      "<model name='m'><static>true</static><link name='l'><collision name='c'><geometry><mesh>"
      "<uri>model://zup_course/meshes/missing.dae</uri></mesh></geometry></collision>"
      "<visual name='v'><geometry><box><size>1 1 1</size></box></geometry></visual></link></model>");
  ASSERT_EQ(l.errors.size(), 1u);
  EXPECT_THAT(l.errors[0], HasSubstr("model 'm' link 'l' collision 'c': mesh "
                                     "'model://zup_course/meshes/missing.dae' not found (tried "));
  EXPECT_THAT(l.errors[0], HasSubstr(kData + "worlds/models/zup_course/meshes/missing.dae"));
  EXPECT_THAT(l.errors[0], HasSubstr("; the collision is left out"));
  const ModelDescription* m = model(l.world, "m");
  ASSERT_NE(m, nullptr);
  EXPECT_TRUE(m->links[0].collisions.empty());
  EXPECT_EQ(m->links[0].visuals.size(), 1u);
  EXPECT_NE(model(l.world, "good"), nullptr);
  EXPECT_THAT(strictError("<model name='m'><static>true</static><link name='l'><collision name='c'>"
                          "<geometry><mesh><uri>meshes/missing.stl</uri></mesh></geometry>"
                          "</collision></link></model>"),
              HasSubstr("mesh 'meshes/missing.stl' not found"));
}

TEST(WorldMeshes, MeshesThatCannotBeUsedAreErrorsAndTheRestLoads) {
  struct Case {
    std::string mesh_xml, expected;
  };
  const std::vector<Case> cases = {
      {"<uri>meshes/unreadable.dae</uri>", "meshes/unreadable.dae': unreadable"},
      {"<uri>meshes/collada_no_geometry.dae</uri>", "meshes/collada_no_geometry.dae': no triangles"},
      {"<uri>meshes/stl_ascii.stl</uri><scale>1 0 1</scale>",
       "collision 'c': <mesh> <scale> '1 0 1' must be > 0 in x, y and z (mesh 'meshes/stl_ascii.stl')"},
      {"<uri>meshes/stl_ascii.stl</uri><scale>-1 1 1</scale>", "<scale> '-1 1 1' must be > 0"},
      {"<uri>meshes/collada_submeshes.dae</uri><submesh><name>middle</name></submesh>",
       "no submesh 'middle' (its parts: 'left', 'right')"},
      {"<uri>http://example.com/x.dae</uri>", "unsupported scheme"},
      // Issue 43: a directory or a device is said to be one (not "not found"), and a file that
      // crashed assimp is an error naming its line.
      {"<uri>meshes</uri>", "mesh 'meshes' (" + kData + "meshes) is a directory, not a mesh file"},
      {"<uri>/dev/zero</uri>", "mesh '/dev/zero' (/dev/zero) is not a regular file (a character device)"},
      {"<uri>fuzz_regressions/mesh/collada_node_instances_itself.dae</uri>",
       "collada_node_instances_itself.dae:26: COLLADA <instance_node url='#a'>: instances a node inside "
       "itself ('a' -> 'a'): a node cycle"},
  };
  for (const Case& c : cases) {
    const Loaded l = load(meshModel("bad", c.mesh_xml));
    ASSERT_EQ(l.errors.size(), 1u) << c.mesh_xml;
    EXPECT_THAT(l.errors[0], HasSubstr("test.world:1: model 'bad' link 'l' collision 'c': "));
    EXPECT_THAT(l.errors[0], HasSubstr(c.expected));
    EXPECT_THAT(l.errors[0], HasSubstr("; the collision is left out"));
    ASSERT_NE(model(l.world, "bad"), nullptr);
    EXPECT_TRUE(model(l.world, "bad")->links[0].collisions.empty());
    ASSERT_NE(model(l.world, "good"), nullptr) << c.mesh_xml;
    EXPECT_EQ(model(l.world, "good")->links[0].collisions.size(), 1u);
    EXPECT_THAT(strictError(meshModel("bad", c.mesh_xml)), HasSubstr(c.expected));
  }
}

TEST(WorldMeshes, ErrorsGoToTheWarningSinkWhenNoErrorSinkIsGiven) {
  std::vector<std::string> warnings;
  WorldLoadOptions o;
  o.warn = [&](const std::string& w) { warnings.push_back(w); };
  const WorldDescription w =
      loadWorldString(worldWith(meshModel("bad", "<uri>meshes/unreadable.dae</uri>")), "t.world", kData, o);
  ASSERT_EQ(warnings.size(), 1u);
  EXPECT_THAT(warnings[0], HasSubstr("unreadable"));
  EXPECT_EQ(w.models.size(), 1u);
}

}  // namespace
}  // namespace tianracer_sim

int main(int argc, char** argv) {
  ::testing::InitGoogleTest(&argc, argv);  // gtest only: gmock matchers are header-only
  return RUN_ALL_TESTS();
}
