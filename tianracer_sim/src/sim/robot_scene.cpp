#include "tianracer_sim/sim/robot_scene.h"

#include <algorithm>

#include <urdf_model/model.h>

#include "tianracer_sim/physics/rigid_tree.h"

namespace tianracer_sim {

namespace {

bool toShape(const urdf::GeometrySharedPtr& geometry, const RobotModel& model, Shape* shape) {
  if (!geometry) return false;
  // An unresolved mesh is left out: the loader warned.
  return shapeFromUrdf(*geometry, [&model](const std::string& uri) {
    const auto it = model.mesh_paths.find(uri);
    return it == model.mesh_paths.end() ? std::string() : it->second;
  }, shape);
}

}  // namespace

RobotSceneBodies addRobotToScene(const RobotModel& model, const std::string& robot_name,
                                 Scene* scene) {
  RobotSceneBodies out;
  std::vector<urdf::LinkSharedPtr> links;
  model.urdf->getLinks(links);
  for (const urdf::LinkSharedPtr& link : links) {
    if (link->visual_array.empty() && link->collision_array.empty()) continue;
    SceneBody body;
    body.name = robot_name + "::" + link->name;
    body.model = robot_name;
    body.is_static = false;
    const int index = scene->addBody(body);
    out.links.emplace_back(index, link->name);

    std::string gazebo_material;
    if (const auto ext = model.ext.links.find(link->name); ext != model.ext.links.end()) {
      gazebo_material = ext->second.material;
    }
    for (const urdf::VisualSharedPtr& visual : link->visual_array) {
      SceneItem item;
      item.body = index;
      item.X_BS = toIsometry(visual->origin);
      item.visual = true;
      if (!toShape(visual->geometry, model, &item.shape)) continue;
      if (!gazebo_material.empty()) {
        item.material.name = gazebo_material;  // the renderer knows Gazebo's colours
      } else if (visual->material) {
        const urdf::Color& c = visual->material->color;
        item.material.ambient = Eigen::Vector4f(c.r, c.g, c.b, c.a);
        item.material.diffuse = item.material.ambient;
        item.material.name = visual->material->name;
      }
      scene->items.push_back(item);
    }
    for (const urdf::CollisionSharedPtr& collision : link->collision_array) {
      SceneItem item;
      item.body = index;
      item.X_BS = toIsometry(collision->origin);
      item.visual = false;
      item.collision = true;
      if (!toShape(collision->geometry, model, &item.shape)) continue;
      scene->items.push_back(item);
    }
  }
  return out;
}

void updateRobotScene(const PhysicsRobot& robot, const RobotSceneBodies& bodies, Scene* scene) {
  for (const auto& [index, link] : bodies.links) {
    scene->bodies[index].X_WB = robot.linkPose(link);
  }
}

void removeModelFromScene(const std::string& model, Scene* scene) {
  std::vector<bool> gone(scene->bodies.size(), false);
  for (std::size_t b = 0; b < scene->bodies.size(); ++b) {
    SceneBody& body = scene->bodies[b];
    if (body.model != model || body.name.empty()) continue;
    gone[b] = true;
    body.name.clear();
    body.model.clear();
  }
  auto& items = scene->items;
  items.erase(std::remove_if(items.begin(), items.end(),
                             [&](const SceneItem& item) {
                               return item.body >= 0 &&
                                      item.body < static_cast<int>(gone.size()) && gone[item.body];
                             }),
              items.end());
}

}  // namespace tianracer_sim
