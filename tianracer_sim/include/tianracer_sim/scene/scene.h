// The geometry that sensors see: every visual and collision shape of the world and of every
// robot, attached to bodies whose poses the simulation updates each step. ROS-free, no Bullet.
// Built once (from the world file and the robots' URDFs); afterwards only body poses change.
#ifndef TIANRACER_SIM_SCENE_SCENE_H
#define TIANRACER_SIM_SCENE_SCENE_H

#include <string>
#include <vector>

#include <Eigen/Geometry>

#include "tianracer_sim/geometry/shape.h"

namespace tianracer_sim {

/// Surface colour: Phong-style ambient/diffuse/specular in linear [0, 1] RGBA, and an optional
/// diffuse texture that modulates the lit colour (Ogre's default colour_op modulate).
struct Material {
  Eigen::Vector4f ambient{0.5f, 0.5f, 0.5f, 1.0f};
  Eigen::Vector4f diffuse{0.7f, 0.7f, 0.7f, 1.0f};
  Eigen::Vector4f specular{0.01f, 0.01f, 0.01f, 1.0f};
  std::string name;  // e.g. "Gazebo/Red" when it came from a Gazebo material name
  /// Diffuse texture file (absolute path; PNG or JPEG), "" for none. A file that cannot be
  /// read is drawn with the colours above (the renderer warns once, naming the file).
  std::string texture;
  /// OGRE texture_unit `scale`: the texture's size on the surface, about its centre
  /// (uv' = (uv - 0.5) / scale + 0.5); 1 1 maps the image once onto the shape's UVs.
  Eigen::Vector2f texture_scale{1.0f, 1.0f};
  /// Specular exponent; < 0: Gazebo's stock value for `name`, else the renderer's default.
  float shininess = -1.0f;
  /// Written by the user (SDF <material>, URDF colour): replaces a mesh file's own colours.
  /// Without it a mesh is drawn with its file's materials (COLLADA/OBJ colours, textures).
  bool specified = false;
};

/// A rigid body: the world's static models, each link (or merged link group) of a robot.
struct SceneBody {
  std::string name;      // "<model>::<link>", e.g. "tianracer::left_front_wheel"
  std::string model;     // model/robot name; sensors of one robot may ignore their own body
  bool is_static = true;
  Eigen::Isometry3d X_WB = Eigen::Isometry3d::Identity();  // updated by the simulation
};

/// A shape attached to a body.
struct SceneItem {
  int body = 0;                                            // index into Scene::bodies
  Eigen::Isometry3d X_BS = Eigen::Isometry3d::Identity();  // shape frame in the body frame
  Shape shape;
  Material material;
  bool visual = true;      // drawn by cameras
  bool collision = false;  // hit by rays (and used by physics)
};

/// Light attenuation 1 / (constant + linear d + quadratic d^2) (SDF <attenuation>).
struct Attenuation {
  double constant = 1.0, linear = 0.0, quadratic = 0.0;
};

/// The sun (or any directional light) of the world. Point and spot lights are drawn as
/// directional ones whose colours are dimmed by their attenuation at their height (see
/// litColours).
struct DirectionalLight {
  std::string name;                            // the SDF light's name ("sun" for model://sun)
  Eigen::Vector3d direction{-0.5, 0.1, -0.9};  // world frame, pointing from the light
  Eigen::Vector4f diffuse{0.8f, 0.8f, 0.8f, 1.0f};   // what is drawn
  Eigen::Vector4f specular{0.2f, 0.2f, 0.2f, 1.0f};  // what is drawn
  /// As the world (or set_light_properties) gives them.
  Eigen::Vector4f given_diffuse{0.8f, 0.8f, 0.8f, 1.0f};
  Eigen::Vector4f given_specular{0.2f, 0.2f, 0.2f, 1.0f};
  Attenuation attenuation;
  /// Point and spot lights: height above the ground where the attenuation is evaluated;
  /// < 0 for a directional light (not attenuated, as in Gazebo).
  double attenuation_height = -1.0;
};

/// The attenuation factor of a light as drawn: min(1, 1 / (c + l h + q h^2)) at its height h,
/// 1 for directional lights.
inline double attenuationFactor(const DirectionalLight& l) {
  if (l.attenuation_height < 0.0) return 1.0;
  const double h = l.attenuation_height;
  const Attenuation& a = l.attenuation;
  const double d = a.constant + a.linear * h + a.quadratic * h * h;
  return d > 1e-9 ? (d < 1.0 ? 1.0 : 1.0 / d) : 1.0;
}

/// Sets the drawn colours from the given ones and the attenuation.
inline void litColours(DirectionalLight* l) {
  const float k = static_cast<float>(attenuationFactor(*l));
  l->diffuse = l->given_diffuse;
  l->specular = l->given_specular;
  l->diffuse.head<3>() *= k;
  l->specular.head<3>() *= k;
}

struct Scene {
  std::vector<SceneBody> bodies;
  std::vector<SceneItem> items;
  std::vector<DirectionalLight> lights;
  Eigen::Vector4f ambient{0.4f, 0.4f, 0.4f, 1.0f};
  Eigen::Vector4f sky{0.7f, 0.8f, 0.95f, 1.0f};  // background colour
  bool ground_plane = false;                      // an infinite z = 0 plane with a grid texture

  int addBody(SceneBody body) {
    bodies.push_back(std::move(body));
    return static_cast<int>(bodies.size()) - 1;
  }
};

}  // namespace tianracer_sim

#endif  // TIANRACER_SIM_SCENE_SCENE_H
