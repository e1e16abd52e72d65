// The SDF world subset (docs/worlds.md) as plain structs (tinyxml2), and its insertion into the Scene
// that sensors and the renderer see. ROS-free.
//
// Supported: <sdf><world> with <physics> (max_step_size, real_time_factor, real_time_update_rate,
// gravity, also <world><gravity> as in SDF 1.6), <scene> (ambient, background), <include>
// (model://ground_plane and model://sun built in; any other model folder found through
// GAZEBO_MODEL_PATH, the load options' model_paths, ~/.gazebo/models, ROS packages exporting
// gazebo_model_path and the world's folder: model.config picks the model file, highest SDF
// version <= 1.7; <name>, <pose>, <static> applied; nested <include>/<model> in a model merged
// as "<sub>::<link>"), <light> (directional; point and spot approximated by a directional light,
// see parseLight), static or dynamic <model>s with <pose>, <joint>s and <link>s (<pose>,
// <inertial>, <collision>, <visual>; geometry box, cylinder, sphere, plane, mesh; <material>
// colours or Gazebo script names; <surface><friction><ode> mu/mu2, <surface><contact><ode>
// kp/kd/max_vel/min_depth; <sensor> with its <plugin>s, as a robot's), model <plugin>s, and a saved <state> (model and link poses override <pose>, as
// Gazebo does on load; <insertions>, <deletions>). Everything else is reported once per element
// name through the WarningSink, with file and line; nothing is dropped silently.
#ifndef TIANRACER_SIM_WORLD_WORLD_H
#define TIANRACER_SIM_WORLD_WORLD_H

#include <cstdint>
#include <functional>
#include <map>
#include <optional>
#include <stdexcept>
#include <string>
#include <vector>

#include <Eigen/Geometry>

#include "tianracer_sim/common/sdf_pose.h"
#include "tianracer_sim/model/robot_model.h"  // WarningSink
#include "tianracer_sim/scene/scene.h"
#include "tianracer_sim/world/actor.h"

namespace tianracer_sim {

/// A world file that cannot be used. The message starts with "<file>:<line>: " where a line is
/// known, and names the element, model, link or URI at fault.
using WorldError = InputError;

/// <physics>; defaults are SDF's.
struct PhysicsSettings {
  double max_step_size = 0.001;           // s
  double real_time_factor = 1.0;          // 0 = as fast as possible
  double real_time_update_rate = 1000.0;  // Hz
  Eigen::Vector3d gravity{0.0, 0.0, -9.8};
  /// <ode><solver><friction_model>: pyramid_model (Gazebo's default), cone_model or box_model.
  std::string friction_model = "pyramid_model";
};

/// <surface><friction><ode>: Coulomb coefficients along the two friction directions.
struct Friction {
  double mu = 1.0;
  double mu2 = 1.0;
};

/// <surface><contact><ode>: contact softness and penetration recovery (unset: the physics'
/// defaults, as for a robot link without these tags).
struct ContactDescription {
  std::optional<double> kp, kd, max_vel, min_depth;
  /// <contact><collide_without_contact>: touched (contact sensors see it) but pushes nothing,
  /// as a mud pit or a trigger zone (Gazebo's mud.world).
  bool collide_without_contact = false;
  /// <contact><collide_without_contact_bitmask> (sdformat's default 1): with
  /// collide_without_contact on either side, two collisions meet only when their masks share a
  /// bit (gazebo/physics/ode/ODEPhysics.cc, ODEPhysics::Collide).
  std::uint32_t collide_without_contact_bitmask = 1;
  /// <contact><collide_bitmask> (sdformat's default 0xffff): two collisions collide only when
  /// their masks share a bit (ODEPhysics::Collide; BulletPhysics.cc's broadphase filter alike).
  std::uint32_t collide_bitmask = 0xffff;
};

/// <inertial>: mass, inertia about the centre of mass, and the CoM frame in the link frame.
/// SDF's defaults (mass 1, unit inertia) where a link has none.
struct InertialDescription {
  double mass = 1.0;
  Eigen::Matrix3d inertia = Eigen::Matrix3d::Identity();
  Eigen::Isometry3d X_LI = Eigen::Isometry3d::Identity();
  int line = 0;  // of <inertial>; 0 = none given
};

struct CollisionDescription {
  std::string name;
  Shape shape;
  Eigen::Isometry3d X_LS = Eigen::Isometry3d::Identity();  // shape in its link
  Friction friction;
  int line = 0;
  ContactDescription contact;
};

struct VisualDescription {
  std::string name;
  Shape shape;
  Eigen::Isometry3d X_LS = Eigen::Isometry3d::Identity();
  Material material;
  int line = 0;
};

struct LinkDescription {
  std::string name;
  Eigen::Isometry3d X_ML = Eigen::Isometry3d::Identity();  // link in its model
  InertialDescription inertial;                            // used for dynamic models only
  /// <self_collide>: collides with the model's other links (Gazebo: a pair collides when
  /// either link says so and no joint joins them).
  bool self_collide = false;
  /// <gravity>: false, the link feels no gravity (Gazebo's Link::SetGravityMode).
  bool gravity = true;
  std::vector<CollisionDescription> collisions;
  std::vector<VisualDescription> visuals;
  /// <sensor>s, in the form robots' <gazebo reference> sensors take (SensorSpec::link is this
  /// link's name, "<sub>::<link>" in a merged nested model): the Simulator sets them up with
  /// the same sensor registry as a robot's (Gazebo: sensors::SensorManager makes a link's
  /// sensors whatever model the link belongs to, gazebo/sensors/SensorManager.cc).
  std::vector<SensorSpec> sensors;
  int line = 0;
};

/// <joint> of a model (sim/world_physics.h simulates fixed, revolute, continuous and
/// prismatic ones; other types are held fixed). Defaults are SDF's.
struct JointDescription {
  std::string name;
  std::string type;  // "fixed", "revolute", ...
  std::string parent, child;  // link names, or "world"
  /// The joint frame J in the child link's frame (<pose>, SDF: relative to the child link).
  Eigen::Isometry3d X_CJ = Eigen::Isometry3d::Identity();
  /// <axis><xyz>, unit, in the joint frame J (an axis given in the model frame, by
  /// <use_parent_model_frame> or expressed_in="__model__", is turned into J when the model is
  /// read).
  Eigen::Vector3d axis = Eigen::Vector3d::UnitZ();
  /// <axis><limit>: lower/upper (rad or m; SDF's +-1e16 = none), effort and velocity (< 0 =
  /// none).
  double lower = -1e16, upper = 1e16, effort = -1.0, velocity = -1.0;
  /// <axis><dynamics>.
  double damping = 0.0, friction = 0.0, spring_reference = 0.0, spring_stiffness = 0.0;
  int line = 0;
};

struct ModelDescription {
  std::string name;
  bool is_static = false;
  /// <allow_auto_disable>: a resting dynamic model may be put to sleep (Gazebo's default).
  bool allow_auto_disable = true;
  Eigen::Isometry3d X_WM = Eigen::Isometry3d::Identity();
  std::vector<LinkDescription> links;
  std::vector<JointDescription> joints;
  /// <plugin>s of the model. Those that publish like sensors (libgazebo_ros_p3d,
  /// libgazebo_ros_imu: plugins/sensor_registry.h) are set up as a robot's model plugins; the
  /// Simulator reports the others as not simulated. A nested model's come with its bodyName
  /// as "<sub>::<link>".
  std::vector<PluginSpec> plugins;
  int line = 0;
};

/// <actor> without its skin (world/actor.h, docs/actors.md): `model` holds its name, its
/// <pose> (X_WM, where it stands until its script moves it) and its <link>s, moved together by
/// `script` in sim time, gravity off, as kinematic bodies.
struct ActorDescription {
  ModelDescription model;
  ActorScript script;
  int line = 0;
};

struct WorldDescription {
  std::string name;    // <world name=...>
  std::string source;  // the file (or the name given to loadWorldString)
  PhysicsSettings physics;
  /// model://ground_plane: Gazebo's infinite z = 0 plane (collision friction mu 100, mu2 50).
  bool ground_plane = false;
  Eigen::Isometry3d X_WG = Eigen::Isometry3d::Identity();  // ground plane pose (its <pose>)
  Friction ground_friction{100.0, 50.0};
  /// model://sun: Gazebo's sun (direction -0.5 0.1 -0.9, diffuse 0.8, specular 0.2).
  std::optional<DirectionalLight> sun;
  std::vector<DirectionalLight> lights;  // other <light type="directional">
  std::optional<Eigen::Vector4f> ambient;     // <scene><ambient>
  std::optional<Eigen::Vector4f> background;  // <scene><background>
  std::vector<ModelDescription> models;
  /// <actor>s; an actor whose <script> is broken is left out (WorldLoadOptions::error).
  std::vector<ActorDescription> actors;
};

struct WorldLoadOptions {
  WarningSink warn;  // may be empty: warnings are then dropped
  /// Folders searched for model://<name>/... mesh URIs, after $GAZEBO_MODEL_PATH and before
  /// the world file's folder and its models/ subfolder.
  std::vector<std::string> model_paths;
  /// package:// lookup for mesh URIs ("" when unknown); may be empty.
  std::function<std::string(const std::string& package)> find_package;
  /// Check every mesh on load: the file exists and is a mesh (mesh/mesh_loader.h: readable,
  /// with triangles, the <submesh> there). false: paths are only resolved.
  bool require_meshes = true;
  /// Receives each error that leaves part of the world out, the way Gazebo logs such an error
  /// and loads the rest (sdformat's parser skips an <include> it cannot find, MeshShape has no
  /// mesh): an <include> whose model is not found (naming the URI and every folder searched), a
  /// mesh that is not found, cannot be read, holds no triangles or lacks the <submesh>, a mesh
  /// <scale> that is not > 0. The model, or the collision or visual, is left out. Empty: they go
  /// to `warn`.
  WarningSink error;
  /// Throw WorldError at the first such error instead (the node's ~strict_world, for CI).
  bool strict = false;
  /// A map world's wall height (m) where its YAML sets no wall_height (map_world.h).
  double map_wall_height = 0.5;
};

/// Reads a world file; a .yaml file is a ROS map (map_world.h). Throws WorldError (a missing
/// file names the path).
WorldDescription loadWorldFile(const std::string& path, const WorldLoadOptions& options = {});

/// Parses world XML; `source` names it in messages and relative URIs resolve against
/// `base_dir`. Never crashes on any input (the fuzzing entry point).
WorldDescription loadWorldString(const std::string& xml, const std::string& source,
                                 const std::string& base_dir,
                                 const WorldLoadOptions& options = {});

/// Parses one model as a model file of an <include> (<sdf><model> or a bare <model>), e.g.
/// what spawn_sdf_model receives. Throws WorldError naming `source` and the line.
ModelDescription loadModelString(const std::string& xml, const std::string& source,
                                 const std::string& base_dir,
                                 const WorldLoadOptions& options = {});

/// The names of the worlds shipped in tianracer_sim/worlds/.
std::vector<std::string> shippedWorldNames();

/// The sim's `world` argument: a shipped name ("empty", "walled_room", "racetrack", i.e.
/// <worlds_dir>/<name>.world) or a path to a .world/.sdf file. Returns the path; throws
/// WorldError naming the argument (and the shipped names) when neither exists.
std::string resolveWorld(const std::string& arg, const std::string& worlds_dir);

/// Appends the world to the scene: one body "<model>::<link>" per link (static models' bodies
/// are static; dynamic ones start at their initial pose and the simulation moves them), one
/// item per collision (collision only) and per visual (visual only), the sun and lights, the
/// scene colours. model://ground_plane sets Scene::ground_plane and adds a static body
/// "ground_plane::link" with an infinite collision plane, so rays hit the ground.
/// Returns the index of each body added, by name.
std::map<std::string, int> addToScene(const WorldDescription& world, Scene& scene);

/// One player per world.actors entry (same order), for physics steps of `dt` s.
std::vector<ActorPlayer> actorPlayers(const WorldDescription& world, double dt);

/// Moves each actor's scene bodies ("<actor>::<link>", added by addToScene) to where its script
/// puts them at sim time `t`: the actor's pose times the link's <pose>.
void updateActorScene(const WorldDescription& world, std::vector<ActorPlayer>* players, double t,
                      Scene* scene);

}  // namespace tianracer_sim

#endif  // TIANRACER_SIM_WORLD_WORLD_H
