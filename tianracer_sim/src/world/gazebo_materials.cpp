// Gazebo's stock script materials (media/materials/scripts/gazebo.material, Gazebo 11): ambient,
// diffuse and specular as written there; textured ones (Wood, WoodFloor...) by their mean colour.
#include <array>
#include <cstring>

#include "tianracer_sim/world/world.h"

namespace tianracer_sim {

namespace {

struct Entry {
  const char* name;
  std::array<float, 3> ambient, diffuse, specular;
};

constexpr Entry kMaterials[] = {
    {"Gazebo/Grey", {0.3f, 0.3f, 0.3f}, {0.7f, 0.7f, 0.7f}, {0.01f, 0.01f, 0.01f}},
    {"Gazebo/DarkGrey", {0.175f, 0.175f, 0.175f}, {0.175f, 0.175f, 0.175f}, {0.175f, 0.175f, 0.175f}},
    {"Gazebo/LightGrey", {0.6f, 0.6f, 0.6f}, {0.8f, 0.8f, 0.8f}, {0.01f, 0.01f, 0.01f}},
    {"Gazebo/White", {1.0f, 1.0f, 1.0f}, {1.0f, 1.0f, 1.0f}, {0.1f, 0.1f, 0.1f}},
    {"Gazebo/FlatBlack", {0.1f, 0.1f, 0.1f}, {0.1f, 0.1f, 0.1f}, {0.01f, 0.01f, 0.01f}},
    {"Gazebo/Black", {0.0f, 0.0f, 0.0f}, {0.0f, 0.0f, 0.0f}, {0.1f, 0.1f, 0.1f}},
    {"Gazebo/Red", {1.0f, 0.0f, 0.0f}, {1.0f, 0.0f, 0.0f}, {0.1f, 0.1f, 0.1f}},
    {"Gazebo/RedBright", {0.87f, 0.26f, 0.07f}, {0.87f, 0.26f, 0.07f}, {0.87f, 0.26f, 0.07f}},
    {"Gazebo/Green", {0.0f, 1.0f, 0.0f}, {0.0f, 1.0f, 0.0f}, {0.1f, 0.1f, 0.1f}},
    {"Gazebo/Blue", {0.0f, 0.0f, 1.0f}, {0.0f, 0.0f, 1.0f}, {0.1f, 0.1f, 0.1f}},
    {"Gazebo/SkyBlue", {0.13f, 0.44f, 0.7f}, {0.0f, 0.0f, 1.0f}, {0.1f, 0.1f, 0.1f}},
    {"Gazebo/Yellow", {1.0f, 1.0f, 0.0f}, {1.0f, 1.0f, 0.0f}, {0.0f, 0.0f, 0.0f}},
    {"Gazebo/ZincYellow", {0.9725f, 0.9529f, 0.2078f}, {0.9725f, 0.9529f, 0.2078f}, {0.9725f, 0.9529f, 0.2078f}},
    {"Gazebo/DarkYellow", {0.7f, 0.7f, 0.0f}, {0.7f, 0.7f, 0.0f}, {0.0f, 0.0f, 0.0f}},
    {"Gazebo/Purple", {1.0f, 0.0f, 1.0f}, {1.0f, 0.0f, 1.0f}, {0.1f, 0.1f, 0.1f}},
    {"Gazebo/Turquoise", {0.0f, 1.0f, 1.0f}, {0.0f, 1.0f, 1.0f}, {0.1f, 0.1f, 0.1f}},
    {"Gazebo/Orange", {1.0f, 0.5088f, 0.0468f}, {1.0f, 0.5088f, 0.0468f}, {0.5f, 0.5f, 0.5f}},
    {"Gazebo/Indigo", {0.33f, 0.0f, 0.5f}, {0.33f, 0.0f, 0.5f}, {0.1f, 0.1f, 0.1f}},
    {"Gazebo/Gold", {0.4f, 0.2f, 0.0f}, {0.9f, 0.7f, 0.2f}, {0.5f, 0.5f, 0.5f}},
    {"Gazebo/Wood", {0.5f, 0.35f, 0.2f}, {0.6f, 0.42f, 0.24f}, {0.1f, 0.1f, 0.1f}},
    {"Gazebo/WoodFloor", {0.45f, 0.3f, 0.18f}, {0.55f, 0.38f, 0.22f}, {0.1f, 0.1f, 0.1f}},
    {"Gazebo/Bricks", {0.5f, 0.25f, 0.2f}, {0.6f, 0.3f, 0.25f}, {0.05f, 0.05f, 0.05f}},
};

Eigen::Vector4f rgba(const std::array<float, 3>& c) { return {c[0], c[1], c[2], 1.0f}; }

}  // namespace

std::optional<Material> gazeboMaterial(const std::string& name) {
  for (const Entry& e : kMaterials) {
    if (name == e.name) {
      Material m;
      m.ambient = rgba(e.ambient);
      m.diffuse = rgba(e.diffuse);
      m.specular = rgba(e.specular);
      m.name = name;
      return m;
    }
  }
  return std::nullopt;
}

}  // namespace tianracer_sim
