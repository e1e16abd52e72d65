#include "tianracer_sim/scene/materials.h"

#include <algorithm>
#include <map>

namespace tianracer_sim {
namespace {

struct Entry {
  float ambient[3];
  float diffuse[3];
  float specular[3];
  float shininess;
};

// gazebo-classic media/materials/scripts/gazebo.material (gazebo 9-11). Ogre's missing values
// default to ambient 1 1 1, diffuse 1 1 1, specular 0 0 0 with shininess 0; those defaults
// are written out here. Textured materials get the mean colour of their texture on top of
// their colours (we draw no textures), marked "texture".
const std::map<std::string, Entry>& table() {
  static const std::map<std::string, Entry> t = {
      {"Gazebo/Grey", {{.3f, .3f, .3f}, {.7f, .7f, .7f}, {.01f, .01f, .01f}, 1.5f}},
      {"Gazebo/DarkGrey", {{.175f, .175f, .175f}, {.175f, .175f, .175f}, {.175f, .175f, .175f}, 1.5f}},
      // Not a stock material (Gazebo shows an unknown name as its default); a light grey in
      // the style of Grey, as robots that use the name expect.
      {"Gazebo/LightGrey", {{.6f, .6f, .6f}, {.8f, .8f, .8f}, {.2f, .2f, .2f}, 12.5f}},
      {"Gazebo/White", {{1, 1, 1}, {1, 1, 1}, {.1f, .1f, .1f}, 128}},
      {"Gazebo/FlatBlack", {{.1f, .1f, .1f}, {.1f, .1f, .1f}, {.01f, .01f, .01f}, 1}},
      {"Gazebo/Black", {{0, 0, 0}, {0, 0, 0}, {.1f, .1f, .1f}, 5}},
      {"Gazebo/Red", {{1, 0, 0}, {1, 0, 0}, {.1f, .1f, .1f}, 1}},
      {"Gazebo/RedBright", {{.87f, .26f, .07f}, {.87f, .26f, .07f}, {.87f, .26f, .07f}, 1}},
      {"Gazebo/Green", {{0, 1, 0}, {0, 1, 0}, {.1f, .1f, .1f}, 1}},
      {"Gazebo/Blue", {{0, 0, 1}, {0, 0, 1}, {.1f, .1f, .1f}, 1}},
      {"Gazebo/SkyBlue", {{.13f, .44f, .70f}, {0, 0, 1}, {.1f, .1f, .1f}, 1}},
      {"Gazebo/Yellow", {{1, 1, 0}, {1, 1, 0}, {0, 0, 0}, 0}},
      {"Gazebo/ZincYellow", {{.9725f, .9529f, .2078f}, {.9725f, .9529f, .2078f}, {.9725f, .9529f, .2078f}, 1}},
      {"Gazebo/DarkYellow", {{.7f, .7f, 0}, {.7f, .7f, 0}, {0, 0, 0}, 0}},
      {"Gazebo/Purple", {{1, 0, 1}, {1, 0, 1}, {.1f, .1f, .1f}, 1}},
      {"Gazebo/Turquoise", {{0, 1, 1}, {0, 1, 1}, {.1f, .1f, .1f}, 1}},
      // "specular 0.5 0.5 0.5 128": four values, the 4th is the shininess.
      {"Gazebo/Orange", {{1, .5088f, .0468f}, {1, .5088f, .0468f}, {.5f, .5f, .5f}, 128}},
      {"Gazebo/Indigo", {{.33f, 0, .5f}, {.33f, 0, .5f}, {.1f, .1f, .1f}, 1}},
      {"Gazebo/Gold", {{.4f, .24869f, .020759f}, {.8f, .64869f, .120759f}, {.4f, .4f, .4f}, 12.5f}},
      // texture wood.jpg (ambient 1, diffuse 1): its mean colour, a mid brown.
      {"Gazebo/Wood", {{.55f, .38f, .22f}, {.55f, .38f, .22f}, {.2f, .2f, .2f}, 12.5f}},
      // texture WoodFloor (wood floor boards): their mean colour.
      {"Gazebo/WoodFloor", {{.45f, .3f, .18f}, {.55f, .38f, .22f}, {.1f, .1f, .1f}, 12.5f}},
      // texture bricks: their mean colour, a dull red.
      {"Gazebo/Bricks", {{.5f, .25f, .2f}, {.6f, .3f, .25f}, {.05f, .05f, .05f}, 1}},
      // texture WoodPallet.png (ambient .5, diffuse 1).
      {"Gazebo/WoodPallet", {{.3f, .24f, .16f}, {.6f, .48f, .32f}, {0, 0, 0}, 0.5f}},
      // The rest of gazebo.material's visible materials, by the same rule: the first pass's
      // colours (Ogre's defaults where it gives none), times the mean colour of its texture
      // (the textures of gazebo-classic media/materials/textures). Not drawn: transparency (the
      // *Transparent ones are opaque here, their manual colour lit), emissive glow, wireframe.
      // Left out: the sensors' and GUI's own (DepthMap, LaserScan*, *Overlay, skies, lens maps,
      // Editor*, BuildingFrame's alpha frame).
      {"Gazebo/RedTransparent", {{1, 0, 0}, {1, 0, 0}, {0, 0, 0}, 0}},
      {"Gazebo/RedGlow", {{1, 0, 0}, {1, 0, 0}, {0, 0, 0}, 128}},
      {"Gazebo/TurquoiseGlowOutline", {{1, 1, 1}, {0, 1, 1}, {.1f, .1f, .1f}, 128}},
      {"Gazebo/GreenTransparent", {{0, 1, 0}, {0, 1, 0}, {0, 0, 0}, 0}},
      {"Gazebo/BlueTransparent", {{0, 0, 1}, {0, 0, 1}, {0, 0, 0}, 0}},
      {"Gazebo/DarkMagentaTransparent", {{.6f, 0, .6f}, {.6f, 0, .6f}, {0, 0, 0}, 0}},
      {"Gazebo/GreyTransparent", {{.5f, .5f, .5f}, {.5f, .5f, .5f}, {0, 0, 0}, 0}},
      {"Gazebo/BlackTransparent", {{0, 0, 0}, {0, 0, 0}, {0, 0, 0}, 0}},
      {"Gazebo/YellowTransparent", {{1, 1, 0}, {1, 1, 0}, {0, 0, 0}, 0}},
      {"Gazebo/OrangeTransparent", {{1, .44f, 0}, {1, .44f, 0}, {0, 0, 0}, 0}},
      {"Gazebo/LightOn", {{0, 1, 0}, {0, 1, 0}, {0, 0, 0}, 0}},
      {"Gazebo/LightOff", {{1, 0, 0}, {1, 0, 0}, {0, 0, 0}, 0}},
      {"Gazebo/LightBlueLaser", {{.5f, .5f, 1}, {.5f, .5f, 1}, {0, 0, 0}, 0}},
      {"Gazebo/BlueLaser", {{0, 0, 1}, {0, 0, 1}, {0, 0, 0}, 0}},
      // texture com.png (ambient 0.5, diffuse 1): its mean colour
      {"Gazebo/CoM", {{.25f, .25f, .25f}, {.5f, .5f, .5f}, {0, 0, 0}, 0}},
      {"Gazebo/JointAnchor", {{1, 1, 1}, {1, 1, 1}, {1, 1, 1}, 1}},
      // texture ceiling_tiled.jpg (ambient 0.5, diffuse 1): its mean colour
      {"Gazebo/CeilingTiled", {{.459f, .459f, .459f}, {.919f, .919f, .919f}, {0, 0, 0}, 0}},
      // texture paintedWall.jpg (ambient 1, diffuse 1): its mean colour
      {"Gazebo/PaintedWall", {{.898f, .772f, .463f}, {.898f, .772f, .463f}, {0, 0, 0}, 0}},
      // texture pioneerBody.jpg (ambient 0.5, diffuse 1): its mean colour
      {"Gazebo/PioneerBody", {{.442f, 0, 0}, {.884f, 0, 0}, {.5f, 0, 0}, 10}},
      {"Gazebo/Pioneer2Body", {{.481f, .000123f, .000123f}, {.681f, .000923f, .000923f}, {.5f, .5f, .5f}, 12.5f}},
      // texture road1.jpg (ambient 0.1, diffuse 0.8): its mean colour
      {"Gazebo/Road", {{.0413f, .0411f, .0404f}, {.33f, .329f, .323f}, {.01f, .01f, .01f}, 2}},
      // texture residential.jpg (ambient 0.1, diffuse 0.8): its mean colour
      {"Gazebo/Residential", {{.0476f, .0452f, .0424f}, {.38f, .362f, .339f}, {.01f, .01f, .01f}, 2}},
      // texture residential.jpg (ambient 0.1, diffuse 0.8): its mean colour
      {"Gazebo/Tertiary", {{.0476f, .0452f, .0424f}, {.38f, .362f, .339f}, {.01f, .01f, .01f}, 2}},
      // texture sidewalk.jpg (ambient 0.1, diffuse 0.8): its mean colour
      {"Gazebo/Pedestrian", {{.0583f, .0583f, .0531f}, {.467f, .466f, .425f}, {.01f, .01f, .01f}, 2}},
      // texture sidewalk.jpg (ambient 0.1, diffuse 0.8): its mean colour
      {"Gazebo/Footway", {{.0583f, .0583f, .0531f}, {.467f, .466f, .425f}, {.01f, .01f, .01f}, 2}},
      // texture motorway.jpg (ambient 0.1, diffuse 0.8): its mean colour
      {"Gazebo/Motorway", {{.0411f, .0406f, .0396f}, {.329f, .325f, .317f}, {.01f, .01f, .01f}, 2}},
      // texture motorway.jpg (ambient 0.1, diffuse 0.8): its mean colour
      {"Gazebo/Lanes_6", {{.0411f, .0406f, .0396f}, {.329f, .325f, .317f}, {.01f, .01f, .01f}, 2}},
      // texture trunk.jpg (ambient 0.1, diffuse 0.8): its mean colour
      {"Gazebo/Trunk", {{.0486f, .0459f, .0419f}, {.389f, .368f, .335f}, {.01f, .01f, .01f}, 2}},
      // texture trunk.jpg (ambient 0.1, diffuse 0.8): its mean colour
      {"Gazebo/Lanes_4", {{.0486f, .0459f, .0419f}, {.389f, .368f, .335f}, {.01f, .01f, .01f}, 2}},
      // texture primary.jpg (ambient 0.1, diffuse 0.8): its mean colour
      {"Gazebo/Primary", {{.0413f, .0411f, .0404f}, {.33f, .329f, .323f}, {.01f, .01f, .01f}, 2}},
      // texture primary.jpg (ambient 0.1, diffuse 0.8): its mean colour
      {"Gazebo/Lanes_2", {{.0413f, .0411f, .0404f}, {.33f, .329f, .323f}, {.01f, .01f, .01f}, 2}},
      // texture secondary.jpg (ambient 0.1, diffuse 0.8): its mean colour
      {"Gazebo/Secondary", {{.0483f, .0457f, .0418f}, {.387f, .366f, .334f}, {.01f, .01f, .01f}, 2}},
      // texture secondary.jpg (ambient 0.1, diffuse 0.8): its mean colour
      {"Gazebo/Lane_1", {{.0483f, .0457f, .0418f}, {.387f, .366f, .334f}, {.01f, .01f, .01f}, 2}},
      // texture steps.jpeg (ambient 0.1, diffuse 0.8): its mean colour
      {"Gazebo/Steps", {{.047f, .047f, .047f}, {.376f, .376f, .376f}, {.01f, .01f, .01f}, 2}},
      // texture runway.png (ambient 0.5, diffuse 1): its mean colour
      {"Gazebo/Runway", {{.201f, .201f, .194f}, {.403f, .402f, .387f}, {0, 0, 0}, 0}},
      // texture grass.jpg (ambient 0.5, diffuse 1): its mean colour
      {"Gazebo/Grass", {{.123f, .24f, .0266f}, {.246f, .48f, .0532f}, {0, 0, 0}, 0}},
  };
  return t;
}

const std::map<std::string, std::string>& aliases() {
  // gz-sim's copy of gazebo.material adds the American spellings.
  static const std::map<std::string, std::string> a = {
      {"Gazebo/Gray", "Gazebo/Grey"},
      {"Gazebo/DarkGray", "Gazebo/DarkGrey"},
      {"Gazebo/LightGray", "Gazebo/LightGrey"},
      // "material Gazebo/GreenGlow : Gazebo/Green": the parent's colours and an emissive glow
      // (not drawn).
      {"Gazebo/WhiteGlow", "Gazebo/White"},
      {"Gazebo/GreenGlow", "Gazebo/Green"},
      {"Gazebo/BlueGlow", "Gazebo/Blue"},
      {"Gazebo/YellowGlow", "Gazebo/Yellow"},
      {"Gazebo/PurpleGlow", "Gazebo/Purple"},
      {"Gazebo/TurquoiseGlow", "Gazebo/Turquoise"},
  };
  return a;
}

}  // namespace

std::optional<GazeboMaterial> findGazeboMaterial(const std::string& name) {
  std::string key = name;
  const auto alias = aliases().find(key);
  if (alias != aliases().end()) key = alias->second;
  const auto it = table().find(key);
  if (it == table().end()) return std::nullopt;
  const Entry& e = it->second;
  GazeboMaterial m;
  m.material.ambient = Eigen::Vector4f(e.ambient[0], e.ambient[1], e.ambient[2], 1.0f);
  m.material.diffuse = Eigen::Vector4f(e.diffuse[0], e.diffuse[1], e.diffuse[2], 1.0f);
  m.material.specular = Eigen::Vector4f(e.specular[0], e.specular[1], e.specular[2], 1.0f);
  m.material.name = name;
  m.shininess = e.shininess;
  return m;
}

std::vector<std::string> knownGazeboMaterialNames() {
  std::vector<std::string> names;
  for (const auto& kv : table()) names.push_back(kv.first);
  for (const auto& kv : aliases()) names.push_back(kv.first);
  std::sort(names.begin(), names.end());
  return names;
}

}  // namespace tianracer_sim
