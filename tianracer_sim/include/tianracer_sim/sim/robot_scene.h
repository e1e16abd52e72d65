// A robot's URDF visuals and collisions as Scene bodies, so that lidars and cameras see it;
// one SceneBody per URDF link, posed from the physics every time sensors fire.
#ifndef TIANRACER_SIM_SIM_ROBOT_SCENE_H
#define TIANRACER_SIM_SIM_ROBOT_SCENE_H

#include <string>
#include <vector>

#include "tianracer_sim/model/robot_model.h"
#include "tianracer_sim/physics/world.h"
#include "tianracer_sim/scene/scene.h"

namespace tianracer_sim {

/// The scene bodies of one robot: (Scene body index, URDF link name).
struct RobotSceneBodies {
  std::vector<std::pair<int, std::string>> links;
};

/// Appends every link with a visual or collision as a body named "<robot>::<link>". Visual
/// colours: the link's Gazebo material name (what Gazebo shows) when set, else the URDF
/// <material> colour. Meshes are referenced by their resolved paths (model.mesh_paths).
RobotSceneBodies addRobotToScene(const RobotModel& model, const std::string& robot_name,
                                 Scene* scene);

/// Copies the links' world poses from the physics into the scene bodies.
void updateRobotScene(const PhysicsRobot& robot, const RobotSceneBodies& bodies, Scene* scene);

/// Takes a model's (robot's or world model's) shapes out of the scene (delete_model). Its
/// bodies stay as empty placeholders named "", so that body indices held by others (the
/// robots' RobotSceneBodies, sensors' own bodies) keep pointing at the same bodies.
void removeModelFromScene(const std::string& model, Scene* scene);

}  // namespace tianracer_sim

#endif  // TIANRACER_SIM_SIM_ROBOT_SCENE_H
