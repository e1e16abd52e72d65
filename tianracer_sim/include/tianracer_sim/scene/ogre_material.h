// OGRE material scripts (.material files, as Gazebo models ship them in
// materials/scripts/): the colours and the first texture unit of a named material. ROS-free.
#ifndef TIANRACER_SIM_SCENE_OGRE_MATERIAL_H
#define TIANRACER_SIM_SCENE_OGRE_MATERIAL_H

#include <optional>
#include <string>
#include <vector>

#include <Eigen/Core>

#include "tianracer_sim/common/warning.h"

namespace tianracer_sim {

/// What we take from one `material NAME { technique { pass { ... } } }` block: the first
/// technique's passes merged (later passes override earlier ones, as Gazebo's stock scripts
/// split an ambient pass and a light pass), and the first texture_unit that names a texture.
struct OgreMaterial {
  std::string name;
  std::string file;  // the script it came from
  int line = 0;      // line of its `material` keyword
  std::optional<Eigen::Vector4f> ambient, diffuse, specular;
  float shininess = 0.0f;     // 5th specular value (4th when only 4 are given)
  std::string texture;        // texture_unit's `texture` file name as written
  Eigen::Vector2f texture_scale{1.0f, 1.0f};  // texture_unit's `scale` (1 1 when absent)
};

/// Parses every material of an OGRE script text. Syntax errors (unbalanced braces, a colour
/// that is not 3-4 numbers) are reported to `warn` with file:line and the material is kept
/// with what was read; nothing throws.
std::vector<OgreMaterial> parseOgreMaterials(const std::string& text, const std::string& file,
                                             const WarningSink& warn = {});

/// Looks for material `name` in the *.material files of `folders` (each a folder or a file).
/// Returns nullopt when none defines it.
std::optional<OgreMaterial> findOgreMaterial(const std::string& name,
                                             const std::vector<std::string>& folders,
                                             const WarningSink& warn = {});

}  // namespace tianracer_sim

#endif  // TIANRACER_SIM_SCENE_OGRE_MATERIAL_H
