// OGRE material scripts: colours of the first technique (passes merged), the first
// texture_unit's texture and scale, comments and one-line blocks, and syntax problems
// reported with file and line.
#include <gtest/gtest.h>

#include <string>
#include <vector>

#include "tianracer_sim/scene/ogre_material.h"

namespace tianracer_sim {
namespace {

TEST(SceneOgreMaterial, ColoursTextureAndScale) {
  const std::string text = R"(
import * from "base.material"
material A/Textured : Base   // inherits
{
  receive_shadows off
  technique
  {
    pass ambient_pass
    {
      ambient 0.5 0.4 0.3
    }
    pass light { diffuse 0.9 0.8 0.7 0.6
      specular 0.2 0.2 0.2 40
      texture_unit base { texture floor.jpg
        scale 2 4 } }
  }
  technique { pass { texture_unit { texture other.png } } }
}
material B/Plain
{
  technique { pass {
    ambient 1 0 0 1
    specular 0.1 0.1 0.1 1 5
  } }
}
)";
  std::vector<std::string> warnings;
  const auto mats = parseOgreMaterials(text, "x.material", [&](const std::string& w) { warnings.push_back(w); });
  ASSERT_EQ(mats.size(), 2u);
  const OgreMaterial& a = mats[0];
  EXPECT_EQ(a.name, "A/Textured");
  EXPECT_EQ(a.line, 3);
  ASSERT_TRUE(a.ambient && a.diffuse && a.specular);
  EXPECT_FLOAT_EQ((*a.ambient)[0], 0.5f);
  EXPECT_FLOAT_EQ((*a.diffuse)[3], 0.6f);
  EXPECT_FLOAT_EQ((*a.specular)[0], 0.2f);
  EXPECT_FLOAT_EQ(a.shininess, 40.0f);  // 4 values: the 4th is the shininess
  EXPECT_EQ(a.texture, "floor.jpg");    // the second technique is not read
  EXPECT_FLOAT_EQ(a.texture_scale.x(), 2.0f);
  EXPECT_FLOAT_EQ(a.texture_scale.y(), 4.0f);
  ASSERT_EQ(warnings.size(), 1u);
  EXPECT_NE(warnings[0].find("x.material:3"), std::string::npos) << warnings[0];
  EXPECT_NE(warnings[0].find("inherits from Base"), std::string::npos) << warnings[0];
  const OgreMaterial& b = mats[1];
  EXPECT_EQ(b.name, "B/Plain");
  ASSERT_TRUE(b.specular);
  EXPECT_FLOAT_EQ(b.shininess, 5.0f);  // 5 values: r g b a shininess
  EXPECT_TRUE(b.texture.empty());
}

TEST(SceneOgreMaterial, SyntaxProblemsAreReportedWithFileAndLine) {
  std::vector<std::string> warnings;
  const auto mats = parseOgreMaterials("material M\n{\n technique\n {\n  pass\n  {\n   diffuse red\n"
                                       "   texture_unit { scale 0 1 }\n  }\n }\n",
                                       "bad.material", [&](const std::string& w) { warnings.push_back(w); });
  ASSERT_EQ(mats.size(), 1u);  // kept with what was read
  EXPECT_FALSE(mats[0].diffuse);
  ASSERT_EQ(warnings.size(), 3u);
  EXPECT_NE(warnings[0].find("bad.material:7"), std::string::npos) << warnings[0];
  EXPECT_NE(warnings[0].find("diffuse red"), std::string::npos) << warnings[0];
  EXPECT_NE(warnings[1].find("bad.material:8"), std::string::npos) << warnings[1];
  EXPECT_NE(warnings[2].find("missing '}'"), std::string::npos) << warnings[2];
}

TEST(SceneOgreMaterial, FindSearchesFolders) {
  EXPECT_FALSE(findOgreMaterial("Nope", {"/nonexistent"}));
}

}  // namespace
}  // namespace tianracer_sim
