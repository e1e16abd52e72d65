// SDF <material> of a visual: colours, Gazebo's stock script names, a model's own OGRE
// material script, and PBR albedo maps, into the scene's Material (texture paths resolved).
// ROS-free.
#ifndef TIANRACER_SIM_WORLD_SDF_MATERIAL_H
#define TIANRACER_SIM_WORLD_SDF_MATERIAL_H

#include <string>
#include <vector>

#include <tinyxml2.h>
#include <tianracer_assets/paths.h>

#include "tianracer_sim/common/warning.h"
#include "tianracer_sim/scene/scene.h"

namespace tianracer_sim {

/// Where a <material> is read: for messages ("<source>:<line>: <what>: ...") and for URIs.
struct SdfMaterialContext {
  std::string source;    // the world file
  /// Resolves its URIs: the world file's folder for relative ones, and the parser's model
  /// search path for model:// (tianracer_assets/paths.h, the one resolver).
  tianracer_assets::UriResolver resolver;
  std::string what;      // "model 'm' link 'l' visual 'v'"
  WarningSink warn;
};

/// Reads <material>:
///  - <script><name> a Gazebo stock name (scene/materials.h) or a material defined in an OGRE
///    script found in the <script><uri> folders (model://x/materials/scripts; its texture is
///    looked for in the <uri> folders, the script's folder and its ../textures);
///  - <ambient>, <diffuse>, <specular> (override the script's colours, as in Gazebo);
///  - <pbr><metal><albedo_map> (a texture URI).
/// URIs resolve through ctx.resolver, as the meshes beside them do. A script, material or texture that is not found is warned (naming
/// the file, line and value) and the colours are used; a colour that is not 3-4 numbers
/// throws WorldError.
Material parseSdfMaterial(const tinyxml2::XMLElement* e, const SdfMaterialContext& ctx);

/// The file or folder a material URI names (model://, package://, file://, absolute, or
/// relative to the world file's folder); "" when none exists or the URI is malformed. `tried` (may be null) receives every path looked at.
std::string resolveMaterialUri(const std::string& uri, const SdfMaterialContext& ctx,
                               std::vector<std::string>* tried = nullptr);

}  // namespace tianracer_sim

#endif  // TIANRACER_SIM_WORLD_SDF_MATERIAL_H
