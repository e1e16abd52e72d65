// Gazebo's stock material names (<material>Gazebo/Red</material>) as Phong colours, with the
// values of gazebo-classic's media/materials/scripts/gazebo.material. One table for the world
// loader (which names it knows) and the renderer (their colours). ROS-free.
#ifndef TIANRACER_SIM_SCENE_MATERIALS_H
#define TIANRACER_SIM_SCENE_MATERIALS_H

#include <optional>
#include <string>
#include <vector>

#include "tianracer_sim/scene/scene.h"

namespace tianracer_sim {

/// A material script's colours. Ogre's "ambient pass" and "light pass" of one technique are
/// merged (Gazebo/White: ambient 1 from the first pass, diffuse 1 and specular .1 from the
/// second). `shininess` is the specular exponent (the 5th specular value, 4th when only 4).
struct GazeboMaterial {
  Material material;  // name set to the Gazebo name
  float shininess = 1.0f;
};

/// The stock material of this name, nullopt if we do not know it. Known: Gazebo/Grey (and
/// Gray), DarkGrey (DarkGray), LightGrey (LightGray; not in gazebo.material: Gazebo falls back
/// to its default grey-white, we give a light grey), White, FlatBlack, Black, Red, RedBright,
/// Green, Blue, SkyBlue, Yellow, ZincYellow, DarkYellow, Purple, Turquoise, Orange, Indigo,
/// Gold, Wood, WoodFloor, WoodPallet, Bricks (textures are not drawn: their mean colour is
/// used instead).
std::optional<GazeboMaterial> findGazeboMaterial(const std::string& name);

/// The names findGazeboMaterial() knows, sorted.
std::vector<std::string> knownGazeboMaterialNames();

/// Specular exponent used when a material has no Gazebo name (Ogre's default shininess is 0,
/// which would make every lit surface fully specular; a moderate lobe looks like Gazebo).
constexpr float kDefaultShininess = 16.0f;

}  // namespace tianracer_sim

#endif  // TIANRACER_SIM_SCENE_MATERIALS_H
