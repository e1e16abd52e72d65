// The one name resolver of the state and property services: models, links and joints by
// Gazebo's names ("model", "model::link", "joint" or "model::joint"), as gazebo_ros's
// services address them (gazebo_ros_api_plugin.cpp: World::ModelByName / EntityByName,
// Model::GetLink, Model::GetJoint), and the state of what they name. The ROS side
// (ros/gazebo_interface.h, ros/gazebo_properties.cpp) and the Simulator's property calls both
// find entities here, and nothing else reaches into the simulation for them. ROS-free.
#ifndef TIANRACER_SIM_SIMULATOR_ENTITIES_H
#define TIANRACER_SIM_SIMULATOR_ENTITIES_H

#include <string>
#include <vector>

#include "tianracer_sim/simulator/entity_state.h"
#include "tianracer_sim/plugins/sim_sensor.h"  // ModelId
#include "tianracer_sim/sim/simulation.h"
#include "tianracer_sim/world/world.h"

namespace tianracer_sim {

class Simulator;

/// A model or a link found by name.
struct Entity {
  ModelId id = kNoModel;                    // the Simulator's model (none for the ground plane)
  const SimRobot* robot = nullptr;          // a robot, or
  const ModelDescription* model = nullptr;  // a world-file or spawned SDF model, or
  bool ground_plane = false;                // model://ground_plane
  bool actor = false;                       // an <actor> (model: its links), moved by its script
  /// What moves it: the robot's or the free body's physics; null for a static model.
  PhysicsRobot* body = nullptr;
  std::string model_name;
  std::string link;  // "" = the model itself (its canonical link)
  /// Whether its state changes with time (a robot, a free body, an actor); a static model's
  /// stays where the world put it.
  bool moves() const { return body != nullptr || actor; }
};

/// A movable joint's state, as joint_states reports it.
struct JointReading {
  double position = 0.0, velocity = 0.0, effort = 0.0;
};

/// A movable joint found by name.
struct JointRef {
  PhysicsRobot* body = nullptr;
  int index = -1;
};

class Entities {
 public:
  explicit Entities(Simulator& sim) : sim_(sim) {}

  /// "model" (when allow_model) or "model::link"; a link of a robot may be any URDF link,
  /// merged ones included. Throws InputError saying what is wrong: "'x' names no model (use
  /// "model" or "model::link")", "no model named 'x' (models: ...)", "model 'm' has no link 'l'",
  /// "'m' is not a link: use gazebo's scoped name "model::link"".
  Entity find(const std::string& name, bool allow_model) const;
  /// The world state of an entity (static models: their pose, zero twist).
  EntityState state(const Entity& e) const;
  /// The frame a reference_frame names: the world for "", "world" and "map", else a model's or
  /// link's state. Throws InputError "reference_frame: ...".
  EntityState frame(const std::string& reference_frame) const;
  /// Moves an entity's model base to X_WB with twist V_WB (a static model cannot move);
  /// `stop_joints` as set_model_state (PhysicsRobot::setModelTwist), otherwise the joint rates
  /// are kept (set_link_state). Throws InputError (checkModelState's text) and changes nothing.
  void setBase(const Entity& e, const EntityState& base, bool stop_joints) const;
  /// A movable joint by "joint" (the first model that has one of that name: the world's
  /// models, then the robots, as Gazebo searches its models) or "model::joint". Fixed joints
  /// are merged away and not found. Throws InputError naming the joint.
  JointRef joint(const std::string& name) const;
  /// The base state that puts link `link` (an Entity with a link, of a moving model) in state
  /// `L` with the model moved rigidly, its joints kept (set_link_state: gazebo moves the one
  /// link and lets the joints pull the others after it). Hand it to setBase().
  EntityState baseFor(const Entity& link, const EntityState& L) const;
  /// apply_body_wrench's total on a link this step (world frame, through its centre of mass);
  /// nothing for a static model.
  void applyWrench(const Entity& link, const Eigen::Vector3d& force_W,
                   const Eigen::Vector3d& torque_W) const;
  /// apply_joint_effort's effort on a joint this step.
  void applyJointEffort(const JointRef& joint, double effort) const;
  /// A robot's or moving world model's rigid bodies with their collisions (get_model_properties'
  /// bodies and geoms), and its movable joints (Gazebo's joint list); empty for a static model.
  const std::vector<TreeBody>& bodies(const Entity& e) const;
  const std::vector<JointInfo>& joints(const Entity& e) const;

  /// Every model by name: the ground plane, the world's models, the actors, the robots
  /// (get_world_properties), the names of models().
  std::vector<std::string> modelNames() const;
  /// The one lister: every model, in modelNames()' order (Entity::link empty), and every link
  /// as Gazebo lists them (/gazebo/model_states, /gazebo/link_states): a world model's and an
  /// actor's every link, a robot's rigid bodies (bodyLinks()), the ground plane's "link".
  std::vector<Entity> models() const;
  std::vector<Entity> links() const;

  // --- a model by id: what its bridges read (joint states, ground truth, frames) -------------
  /// The rigid bodies of a robot or moving world model, each named after its first link (what
  /// Gazebo lists after lumping the links joined by fixed joints), the base first; empty for a
  /// static model.
  std::vector<std::string> bodyLinks(ModelId id) const;
  /// Where a robot or moving world model was spawned (its base, in the world).
  Eigen::Isometry3d spawnPose(ModelId id) const;
  /// Movable joint `joint` (Simulator::jointIndex) of a robot or moving world model.
  JointReading jointReading(ModelId id, int joint) const;

 private:
  Simulator& sim_;
};

}  // namespace tianracer_sim

#endif  // TIANRACER_SIM_SIMULATOR_ENTITIES_H
