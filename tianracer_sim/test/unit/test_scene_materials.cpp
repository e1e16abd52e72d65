#include <algorithm>

#include <gtest/gtest.h>

#include "tianracer_sim/scene/materials.h"

namespace tianracer_sim {

TEST(GazeboMaterials, StockNamesWithGazeboMaterialValues) {
  const auto grey = findGazeboMaterial("Gazebo/Grey");
  ASSERT_TRUE(grey);
  EXPECT_FLOAT_EQ(grey->material.ambient[0], 0.3f);
  EXPECT_FLOAT_EQ(grey->material.diffuse[0], 0.7f);
  EXPECT_EQ(grey->material.name, "Gazebo/Grey");
  EXPECT_FLOAT_EQ(findGazeboMaterial("Gazebo/Orange")->shininess, 128.0f);
  for (const char* name : {"Gazebo/WoodFloor", "Gazebo/Bricks", "Gazebo/WoodPallet"}) {
    EXPECT_TRUE(findGazeboMaterial(name)) << name;
  }
}

TEST(GazeboMaterials, AmericanSpellingsAndUnknownNames) {
  const auto gray = findGazeboMaterial("Gazebo/Gray");
  ASSERT_TRUE(gray);
  EXPECT_EQ(gray->material.diffuse, findGazeboMaterial("Gazebo/Grey")->material.diffuse);
  EXPECT_EQ(gray->material.name, "Gazebo/Gray");
  EXPECT_FALSE(findGazeboMaterial("Gazebo/NoSuchColour"));
  EXPECT_FALSE(findGazeboMaterial(""));
  const auto names = knownGazeboMaterialNames();
  EXPECT_TRUE(std::is_sorted(names.begin(), names.end()));
  EXPECT_NE(std::find(names.begin(), names.end(), "Gazebo/Gray"), names.end());
}

}  // namespace tianracer_sim
