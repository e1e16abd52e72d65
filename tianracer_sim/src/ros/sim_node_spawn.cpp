// The sim node's models at run time: spawn_urdf_model and spawn_sdf_model build through the
// start-up path (addRobot, addModelToPhysics), delete_model takes everything back out. Called by
// GazeboInterface on the node's callback thread, between steps.
#include <algorithm>

#include <ros/package.h>

#include "tianracer_sim/ros/sim_node.h"

namespace tianracer_sim {

void SimNode::removeRobotAt(std::size_t index) {
  RobotIo& io = robots_[index];
  if (!io.robot) return;
  const std::string name = io.robot->name;
  // The frame in flight may be one of its cameras'.
  if (camera_worker_) camera_worker_->wait();
  for (std::size_t k = sensors_.size(); k-- > 0;) {
    if (sensor_robot_[k] != index) continue;
    sensors_.erase(sensors_.begin() + static_cast<std::ptrdiff_t>(k));
    sensor_robot_.erase(sensor_robot_.begin() + static_cast<std::ptrdiff_t>(k));
  }
  for (const std::size_t stat : io.stats) stats_[stat].name.clear();
  for (const std::string& topic : io.topics) topic_owner_.erase(topic);
  contacts_->removeRobot(io.robot->id);
  removeModelFromScene(name, &scene_);
  scene_step_ = ~0ull;
  // Publishers and subscribers shut down with their last handle; the command subscribers go
  // before the controllers they point into.
  io.controller_manager.reset();
  io.commands.reset();
  sim_->removeRobot(name);
  io = RobotIo();
}

void SimNode::spawnRobot(const std::string& name, const std::string& urdf,
                         const Eigen::Isometry3d& X_WB) {
  // Its cameras set up on the renderer the frame worker may be drawing with.
  if (camera_worker_) camera_worker_->wait();
  LoadOptions options;
  options.resolver.find_package = [](const std::string& pkg) { return ros::package::getPath(pkg); };
  options.warn = [](const std::string& w) { warnOnce(w); };
  RobotRequest request;
  request.rp = ros::NodeHandle(pnh_, name);
  request.rp.param<std::string>("model_dir", options.resolver.base_dir, "");
  request.model = loadRobotModel(urdf, "spawn_urdf_model '" + name + "'", options);
  request.name = name;
  request.X_WB = X_WB;
  request.spawned = true;
  addRobot(std::move(request));
}

void SimNode::spawnWorldModel(const std::string& name, const std::string& sdf,
                              const Eigen::Isometry3d& X_WM) {
  ModelDescription model = loadModelString(sdf, "spawn_sdf_model '" + name + "'", "",
                                           world_options_);
  // gazebo_ros: the model's own <pose> is relative to initial_pose.
  model.name = name;
  model.X_WM = X_WM * model.X_WM;
  const WorldModelBodies added =
      addModelToPhysics(*world_, model, &sim_->physics(), [](const std::string& w) { warnOnce(w); });
  world_bodies_[name] = added;
  // Static shapes were added link by link, collision by collision.
  std::size_t k = 0;
  for (const LinkDescription& link : model.links) {
    for (std::size_t c = 0; c < link.collisions.size() && k < added.statics.size(); ++c) {
      contacts_->setStaticOwner(added.statics[k++], name, link.name);
    }
  }
  WorldDescription one;
  one.models.push_back(model);
  addToScene(one, scene_);
  scene_step_ = ~0ull;
  world_->models.push_back(std::move(model));
}

void SimNode::deleteModel(const std::string& name) {
  for (std::size_t i = 0; i < robots_.size(); ++i) {
    if (robots_[i].robot && robots_[i].robot->name == name) {
      removeRobotAt(i);
      return;
    }
  }
  const auto it = std::find_if(world_->models.begin(), world_->models.end(),
                               [&](const ModelDescription& m) { return m.name == name; });
  if (it == world_->models.end()) {
    throw std::runtime_error("model '" + name + "' cannot be deleted (the ground plane stays)");
  }
  if (camera_worker_) camera_worker_->wait();
  removeModelFromPhysics(world_bodies_.at(name), &sim_->physics());
  world_bodies_.erase(name);
  removeModelFromScene(name, &scene_);
  scene_step_ = ~0ull;
  world_->models.erase(it);
}

}  // namespace tianracer_sim
