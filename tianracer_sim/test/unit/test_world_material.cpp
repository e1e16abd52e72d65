// SDF <material>: OGRE scripts of a model (model:// through the world's folder and
// GAZEBO_MODEL_PATH), their texture_unit, PBR albedo maps, stock names, and the warnings for
// what is not found.
#include <gtest/gtest.h>

#include <stdlib.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include "tianracer_sim/world/world.h"

#include "common_test_support.h"

namespace tianracer_sim {
namespace {

namespace fs = std::filesystem;

// A fresh folder per test, <tmp>/tianracer_material_XXXXXX, removed at its end.
struct TempDir : test::TempDir {
  TempDir() : test::TempDir("material") {}
};

const char* kScript = R"(// a model's own material
material Board/Checker
{
  technique
  {
    pass
    {
      ambient 0.9 0.8 0.7 1
      diffuse 0.6 0.5 0.4
      specular 0.1 0.1 0.1 1 12
      texture_unit
      {
        texture checker.png
        scale 0.5 0.25
      }
    }
  }
}

material Board/NoTexture
{
  technique { pass { diffuse 0.1 0.2 0.3 1 } }
}

material Board/MissingTexture
{
  technique
  {
    pass
    {
      diffuse 0.3 0.3 0.3 1
      texture_unit { texture gone.png }
    }
  }
}
)";

std::string world(const std::string& material) {
  return "<sdf version='1.6'><world name='w'><model name='board'><static>true</static>"
         "<link name='link'><visual name='v'><geometry><box><size>1 1 1</size></box></geometry>"
         "<material>" + material + "</material></visual></link></model></world></sdf>";
}

// By value: callers pass temporaries (a reference into one would dangle after the statement).
Material visualMaterial(const WorldDescription& w) { return w.models.at(0).links.at(0).visuals.at(0).material; }

// The board world with `material`, loaded from `folder` with its warnings collected.
struct BoardLoader {
  std::string folder;
  std::vector<std::string> warnings;
  WorldLoadOptions options;
  explicit BoardLoader(std::string world_folder) : folder(std::move(world_folder)) {
    options.warn = [this](const std::string& w) { warnings.push_back(w); };
  }
  BoardLoader(const BoardLoader&) = delete;
  BoardLoader& operator=(const BoardLoader&) = delete;
  WorldDescription load(const std::string& material) {
    return loadWorldString(world(material), "test.world", folder, options);
  }
};

// A fresh world folder whose model 'board' has kScript (models/board/materials/scripts), and
// the board world loaded from it.
struct BoardFolder : TempDir, BoardLoader {
  const std::string script = write("models/board/materials/scripts/board.material", kScript);
  BoardFolder() : BoardLoader(path.string()) {}
};

std::string scriptFor(const std::string& name) {
  return "<script><uri>model://board/materials/scripts</uri><uri>model://board/materials/textures</uri>"
         "<name>" + name + "</name></script>";
}

TEST(WorldMaterial, OgreScriptWithTextureUnitResolvesThroughTheWorldsFolder) {
  BoardFolder board;
  const std::string png = board.write("models/board/materials/textures/checker.png", "png bytes");
  std::vector<std::string>& warnings = board.warnings;
  const WorldDescription w = board.load(scriptFor("Board/Checker"));
  EXPECT_TRUE(warnings.empty()) << warnings.front();
  const Material& m = visualMaterial(w);
  EXPECT_EQ(m.name, "Board/Checker");
  EXPECT_TRUE(m.specified);
  EXPECT_FLOAT_EQ(m.ambient[0], 0.9f);
  EXPECT_FLOAT_EQ(m.diffuse[1], 0.5f);
  EXPECT_FLOAT_EQ(m.diffuse[3], 1.0f);
  EXPECT_FLOAT_EQ(m.specular[0], 0.1f);
  EXPECT_FLOAT_EQ(m.shininess, 12.0f);
  EXPECT_EQ(fs::path(m.texture), fs::path(png));
  EXPECT_FLOAT_EQ(m.texture_scale.x(), 0.5f);
  EXPECT_FLOAT_EQ(m.texture_scale.y(), 0.25f);
  // Explicit colours override the script's, as in Gazebo; the texture stays.
  const WorldDescription w2 = board.load(scriptFor("Board/Checker") + "<diffuse>1 0 0 1</diffuse>");
  EXPECT_FLOAT_EQ(visualMaterial(w2).diffuse[0], 1.0f);
  EXPECT_EQ(fs::path(visualMaterial(w2).texture), fs::path(png));
  // A material without texture: colours only.
  const Material& plain = visualMaterial(board.load(scriptFor("Board/NoTexture")));
  EXPECT_FLOAT_EQ(plain.diffuse[2], 0.3f);
  EXPECT_FLOAT_EQ(plain.ambient[0], 1.0f);  // Ogre's default ambient
  EXPECT_TRUE(plain.texture.empty());
}

TEST(WorldMaterial, ModelUrisResolveThroughGazeboModelPath) {
  TempDir models, world_dir;
  models.write("board/materials/scripts/board.material", kScript);
  const std::string png = models.write("board/materials/textures/checker.png", "png bytes");
  setenv("GAZEBO_MODEL_PATH", ("/nonexistent:" + models.path.string()).c_str(), 1);
  BoardLoader board(world_dir.path.string());
  std::vector<std::string>& warnings = board.warnings;
  const WorldDescription w = board.load(scriptFor("Board/Checker"));
  unsetenv("GAZEBO_MODEL_PATH");
  EXPECT_TRUE(warnings.empty()) << warnings.front();
  EXPECT_EQ(fs::path(visualMaterial(w).texture), fs::path(png));
}

TEST(WorldMaterial, MissingTextureWarnsNamingFileLineAndValueAndKeepsTheColour) {
  BoardFolder board;
  std::vector<std::string>& warnings = board.warnings;
  const WorldDescription w = board.load(scriptFor("Board/MissingTexture"));
  const Material& m = visualMaterial(w);
  EXPECT_TRUE(m.texture.empty());
  EXPECT_FLOAT_EQ(m.diffuse[0], 0.3f);
  ASSERT_EQ(warnings.size(), 2u);  // the textures folder <uri> is missing too
  const std::string& t = warnings[1];
  EXPECT_NE(t.find(board.script + ":25"), std::string::npos) << t;  // the material's line
  EXPECT_NE(t.find("'gone.png' not found"), std::string::npos) << t;
  EXPECT_NE(t.find("test.world:1"), std::string::npos) << t;
  EXPECT_NE(t.find("diffuse colour"), std::string::npos) << t;
  EXPECT_NE(warnings[0].find("model://board/materials/textures"), std::string::npos) << warnings[0];
}

TEST(WorldMaterial, UnknownNamesAndAlbedoMaps) {
  BoardFolder board;
  const std::string albedo = board.write("textures/albedo.png", "png bytes");
  std::vector<std::string>& warnings = board.warnings;
  const Material& unknown = visualMaterial(board.load(scriptFor("Board/Nope")));
  EXPECT_EQ(unknown.name, "Board/Nope");
  EXPECT_TRUE(unknown.texture.empty());
  ASSERT_FALSE(warnings.empty());
  EXPECT_NE(warnings.back().find("unknown material 'Board/Nope'"), std::string::npos) << warnings.back();
  warnings.clear();
  // Stock names keep working, with Gazebo's media URI.
  const Material& stock = visualMaterial(board.load(
      "<script><uri>file://media/materials/scripts/gazebo.material</uri><name>Gazebo/Red</name>"
      "</script>"));
  EXPECT_EQ(stock.name, "Gazebo/Red");
  EXPECT_TRUE(warnings.empty()) << warnings.front();
  // PBR albedo map, relative to the world's folder.
  const Material& pbr = visualMaterial(
      board.load("<diffuse>0.5 0.5 0.5 1</diffuse><pbr><metal><albedo_map>textures/albedo.png"
                 "</albedo_map><roughness>0.5</roughness></metal></pbr>"));
  EXPECT_EQ(fs::path(pbr.texture), fs::path(albedo));
  ASSERT_EQ(warnings.size(), 1u);  // <roughness> is not used
  EXPECT_NE(warnings[0].find("<roughness>"), std::string::npos) << warnings[0];
  warnings.clear();
  const Material& missing = visualMaterial(
      board.load("<pbr><metal><albedo_map>textures/none.png</albedo_map></metal></pbr>"));
  EXPECT_TRUE(missing.texture.empty());
  ASSERT_EQ(warnings.size(), 1u);
  EXPECT_NE(warnings[0].find("test.world:1"), std::string::npos) << warnings[0];
  EXPECT_NE(warnings[0].find("'textures/none.png' not found"), std::string::npos) << warnings[0];
  // A colour that is not one is an error naming file and value.
  EXPECT_THROW(board.load("<diffuse>red</diffuse>"), WorldError);
}

}  // namespace
}  // namespace tianracer_sim
