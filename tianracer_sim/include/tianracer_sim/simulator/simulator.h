// The simulation without ROS: a world, its robots and world models, their sensors, the scene
// sensors see, the step, the clock and the lockstep decisions. The ROS node (ros/sim_node.h)
// is bridges around it; a Python environment can drive it directly:
//
//   Simulator sim(loadWorldFile("racetrack.world"), {});
//   RobotSpawn car;  car.name = "tianracer";  car.model = loadRobotModel(urdf, "car", {});
//   car.controllers = specs;  car.drop_to_ground = true;
//   const ModelId id = sim.addRobot(std::move(car));
//   sim.setCommand(id, "left_rear_wheel_velocity_controller", 30.0);
//   sim.step(100);
//   auto* lidar = dynamic_cast<const SimLidar*>(sim.findSensor(id, "laser"));
//   lidar->ranges();
//
// Sensors compute only what is due (their rates in sim time) and wanted (their listener;
// without one, everything due). Camera frames render on a worker thread from a snapshot of the
// step's scene: waitFrames() before reading them. Everything happens on the caller's thread
// except rendering; calls between steps only.
#ifndef TIANRACER_SIM_SIMULATOR_SIMULATOR_H
#define TIANRACER_SIM_SIMULATOR_SIMULATOR_H

#include <cstdint>
#include <functional>
#include <map>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include <Eigen/Geometry>

#include <tianracer_control/joint_controllers.h>

#include "tianracer_sim/common/step_profile.h"
#include "tianracer_sim/common/warning.h"
#include "tianracer_sim/lidar/ray_caster.h"
#include "tianracer_sim/model/robot_model.h"
#include "tianracer_sim/render/renderer.h"
#include "tianracer_sim/scene/scene.h"
#include "tianracer_sim/plugins/model_report.h"
#include "tianracer_sim/sim/contact_tracker.h"
#include "tianracer_sim/simulator/entity_state.h"
#include "tianracer_sim/sim/frame_worker.h"
#include "tianracer_sim/sim/robot_hw_sim.h"
#include "tianracer_sim/sim/robot_scene.h"
#include "tianracer_sim/common/schedule.h"
#include "tianracer_sim/sim/simulation.h"
#include "tianracer_sim/sim/world_physics.h"
#include "tianracer_sim/plugins/sim_sensor.h"
#include "tianracer_sim/simulator/entities.h"
#include "tianracer_sim/simulator/properties.h"
#include "tianracer_sim/simulator/sensor_host.h"
#include "tianracer_sim/world/world.h"

namespace tianracer_sim {

/// Where the simulator's messages go (the ROS node logs them; empty sinks drop them).
struct SimulatorLog {
  WarningSink info;         // what was set up, one line each
  WarningSink warn;         // loaders' and sensors' warnings (repeated per robot: log each once)
  WarningSink error;        // a part left out (a sensor); the rest runs on
  WarningSink frame_error;  // a camera frame failed; may come every frame: throttle
};

struct SimulatorOptions {
  /// Physics step (s) in (0, 0.1]; 0 = the world's <max_step_size>.
  double max_step_size = 0.0;
  /// Seed of the sensors' noise: same seed, same noise.
  std::uint64_t seed = 0;
  SimulatorLog log;
  /// Where each step's time goes (common/step_profile.h): the physics, the contact scan, each
  /// sensor's update, sample and publication, the frame worker's renders. Null: not timed.
  /// Owned by the caller; it outlives the Simulator.
  StepProfile* profile = nullptr;
};

/// A robot to add (start-up and spawn_urdf_model alike).
struct RobotSpawn {
  std::string name;  // unique among the models
  RobotModel model;
  Eigen::Isometry3d X_WB = Eigen::Isometry3d::Identity();
  bool drop_to_ground = false;  // z such that the lowest collision point rests on z = 0
  std::vector<tianracer_control::ControllerSpec> controllers;
  /// gazebo_ros_control's joint_limits and pid_gains parameters (sim/robot_hw_sim.h).
  RobotHwSimParams hw_sim;
  std::string tf_prefix;  // prefixes the frames of its sensors' outputs
  /// Sensor types or names left out (~disable_sensors).
  std::vector<std::string> disabled_sensors;
  /// Called once the robot is in the simulation (physics, controllers, scene), before its
  /// sensors are set up (the ROS node sets up the robot's topics). A throw takes the robot out.
  std::function<void(ModelId)> added;
  /// Called for each sensor before it first runs (the ROS node attaches its publisher). A
  /// throw leaves the sensor out, with the message as the reason.
  std::function<void(SimSensor&)> attach;
};

/// Plain joint states of a robot: every movable joint, in the physics' order.
struct JointStates {
  std::vector<std::string> name;
  std::vector<double> position, velocity, effort;
};

/// Which lockstep waits a step has (Simulator::advance()).
struct StepWaits {
  bool replies = false;  // the driver's answer to this step's sensor data
  bool ticks = false;    // the nodes ticking on this step's /clock
};

class Simulator : public SensorWorld {
 public:
  /// Builds the world's models (static shapes, free bodies) and the scene. Throws
  /// std::invalid_argument for a step outside (0, 0.1] s, PhysicsError / MeshError naming a
  /// model of the world.
  Simulator(WorldDescription world, SimulatorOptions options);
  ~Simulator() override;
  Simulator(const Simulator&) = delete;
  Simulator& operator=(const Simulator&) = delete;

  // --- models ---------------------------------------------------------------------------------
  /// Adds a robot with its controllers and sensors (spawn.added() in between). Throws (a message naming the robot) on bad
  /// input; nothing of the robot stays then. A bad sensor is left out (leftOut()), not thrown.
  ModelId addRobot(RobotSpawn spawn);
  /// Adds a world model (spawn_sdf_model) where model.X_WM says, with the sensors of its links
  /// (as the world's models get theirs). Throws naming the model; nothing of it stays then. A
  /// bad sensor is left out (leftOut()), not thrown.
  ModelId addWorldModel(ModelDescription model);
  /// From now on each sensor of a world model goes through `attach` before it first runs, as
  /// RobotSpawn::attach does for a robot's: those the world brought (made in the constructor,
  /// unattached until now) at once, addWorldModel's as they come. A throw leaves the sensor
  /// out, with the message as the reason (leftOut()). Lets the owner of the publishers (the
  /// ROS node) take a Simulator built before it.
  void attachWorldSensors(std::function<void(SimSensor&)> attach);
  /// Takes a robot or world model out with everything of it (sensors, scene, physics). Throws
  /// std::runtime_error for an unknown name or the ground plane.
  void removeModel(const std::string& name);
  /// The model of that name (robots and world models); kNoModel when none.
  ModelId findModel(const std::string& name) const;
  /// The robot of a model id; nullptr for world models and removed ones.
  SimRobot* robot(ModelId id);
  const SimRobot* robot(ModelId id) const;
  /// Changes whenever a model is added or removed (what a cache of the model list compares).
  std::uint64_t modelsVersion() const { return models_version_; }
  /// Ids of the robots, in the order they were added.
  std::vector<ModelId> robotIds() const;
  /// Ids of every model (world models and robots), in the order they were added.
  std::vector<ModelId> modelIds() const;
  /// The name of model `id` ("" when there is none).
  const std::string& modelName(ModelId id) const;
  /// The physics of model `id`: a robot's, or a world model's free body; nullptr for a static
  /// model. Throws std::out_of_range for an id that names no model.
  const PhysicsRobot* physicsOf(ModelId id) const;
  PhysicsRobot* physicsOf(ModelId id);
  /// Models, links and joints by Gazebo's names, and their states (simulator/entities.h): the
  /// one name resolver of the state and property services.
  Entities entities() const { return Entities(const_cast<Simulator&>(*this)); }
  /// The sensors of model `id` (a robot or a world model) left out, and why (the start-up table's "left out" rows).
  const LeftOut& leftOut(ModelId id) const;

  // --- time -----------------------------------------------------------------------------------
  /// One physics step: controllers (at their period), physics, contacts. Returns the lockstep
  /// waits due at the new time.
  StepWaits advance();
  /// The sensors due at this time: cast, measured or frames requested; handed to listeners.
  void sense();
  /// n times advance() then sense().
  void step(int n = 1);
  double time() const { return sim_.time(); }
  double dt() const override { return sim_.dt(); }
  Eigen::Vector3d gravity() const override { return sim_.physics().options().gravity; }
  std::uint64_t stepCount() const { return sim_.stepCount(); }
  /// gazebo's reset_simulation: time to 0, models to their spawn poses, controllers, sensors'
  /// schedules and histories and lockstep restarted.
  void resetSimulation();
  /// gazebo's reset_world: poses only; time keeps running.
  void resetWorld();
  /// Paused is the run loop's business (advance() steps regardless); kept here so that every
  /// bridge sees the same state.
  bool paused() const { return paused_; }
  void setPaused(bool paused) { paused_ = paused; }
  /// Lockstep: which steps wait for the driver's replies and for the ticks (periods in sim s).
  void setLockstep(bool replies, double reply_period, bool ticks, double tick_period);

  // --- state as plain data --------------------------------------------------------------------
  /// A model's canonical body: pose and twist in the world.
  EntityState modelState(ModelId id) const;
  void jointStates(ModelId robot, JointStates* out) const;
  /// Sets the command of a robot's controller (as its /command topic does). False for an
  /// unknown robot or controller, or a non-finite value (the previous command stays).
  bool setCommand(ModelId robot, const std::string& controller, double value);

  // --- what gazebo_ros's property services read and change (docs/gazebo_interface.md) -------
  /// The physics, joint, link and light properties (simulator/properties.h).
  Properties& properties() { return *properties_; }
  const Properties& properties() const { return *properties_; }

  // --- controllers (controller_manager's load, unload and switch) ------------------------------
  /// The one owner of the robots' controllers (sim/controller_manager.h); its calls take a
  /// robot (robot(id)).
  ControllerManager& controllerManager() { return sim_.controllerManager(); }

  // --- sensors --------------------------------------------------------------------------------
  /// Every sensor, in set-up order (robots' sensors in the order their models list them); they
  /// run in the SensorHost (simulator/sensor_host.h).
  const std::vector<std::unique_ptr<SimSensor>>& sensors() const { return sensors_->sensors(); }
  /// The sensor called `name` on model `id` (model plugins by their plugin name); nullptr if none.
  SimSensor* findSensor(ModelId id, const std::string& name) const { return sensors_->find(id, name); }
  /// Waits for the frame in flight: rendered outputs are complete afterwards.
  void waitFrames();
  /// Contacts begun so far by robot `id` (a pair touching again after a gap counts again).
  std::uint64_t contactCount(ModelId id) const;
  /// Robot `id`'s contacts in the last step (none for a model that is no robot).
  void robotContacts(ModelId id, std::vector<RobotContact>* out) const;
  /// The names a contact of robot `robot` (physics id) carries in a message: its own link, and
  /// the model and link it touches ("ground_plane"/"link" for the ground).
  void contactNames(RobotId robot, const RobotContact& contact, std::string* link,
                    std::string* other_model, std::string* other_link) const;
  /// Whether each step's contacts are tracked (counted for contactCount(), queued in
  /// contacts().due()); on by default. The ROS node turns it on only while something reads
  /// them, as Gazebo's ContactManager::NewContact (physics/ContactManager.cc) makes contacts
  /// only while ~/physics/contacts has subscribers or a contact sensor wants them. Turned
  /// off, the contacts in progress are forgotten: one still there when it resumes is new.
  /// (A bumper reads its link's contacts itself, linkContacts(): it needs no tracking.)
  void setContactTracking(bool on);
  bool contactTracking() const { return track_contacts_; }

  // --- SensorWorld: what sensors read, addressed by model id and link name ---------------------
  const Scene& scene() override;
  RayCaster& caster() override { return caster_; }
  Eigen::Isometry3d linkPose(const LinkRef& link) const override;
  bool linkState(const LinkRef& link, LinkState* state) const override;
  void linkContacts(const LinkRef& link, std::vector<LinkContact>* out) override;
  void requestFrame(const FrameRequest& request) override { sensors_->requestFrame(request); }
  int jointIndex(ModelId model, const std::string& joint, std::string* parent_link,
                 std::string* child_link) const override;
  double jointPosition(ModelId model, int joint) const override;
  double jointVelocity(ModelId model, int joint) const override;
  void setJointVelocity(ModelId model, int joint, double omega, double max_effort) override;
  LinkState modelFrameState(ModelId model) const override;
  bool setModelVelocity(ModelId model, const Eigen::Vector3d& linear_W,
                        const Eigen::Vector3d& angular_W) override;

  // --- the parts, for the bridges -------------------------------------------------------------
  const WorldDescription& world() const { return *world_; }
  const ContactTracker& contacts() const { return contacts_; }
  const SimulatorOptions& options() const { return options_; }
  /// SimulatorOptions::profile (null when not profiling).
  StepProfile* profile() const { return options_.profile; }

 private:
  /// One model: a robot (robot != nullptr) or a world model. Kept as an empty slot once
  /// removed, so that ids stay indices.
  struct Model {
    std::string name;  // "" once removed
    SimRobot* robot = nullptr;
    RobotSceneBodies scene_bodies;  // robots
    WorldModelBodies bodies;        // world models
    int actor = -1;                 // <actor>: its index in world_->actors (actor_players_)
    LeftOut left_out;
  };
  const Model* model(ModelId id) const;
  void setUpSensors(ModelId id, const RobotSpawn& spawn);
  /// The sensors of world model `id`'s links, attached through world_attach_.
  void setUpWorldModelSensors(ModelId id);
  /// One sensor of robot or world model `id`; a bad one is reported and left out.
  void setUpSensor(ModelId id, const SensorSpec& spec, const std::string& tf_prefix,
                   const std::function<void(SimSensor&)>& attach);
  void restartLockstep(double t);
  void updateScene();

  SimulatorOptions options_;
  std::function<void(SimSensor&)> world_attach_;  // attachWorldSensors()
  std::unique_ptr<WorldDescription> world_;
  Simulation sim_;
  std::vector<Model> models_;
  std::uint64_t models_version_ = 0;  // modelsVersion()
  Scene scene_;  // what sensors see: the world's models and every robot's links
  std::uint64_t scene_step_ = ~0ull;  // step count the scene's poses belong to
  RayCaster caster_;
  // The world's <actor>s (world/actor.h), played to the sim time asked (modelState, the scene).
  mutable std::vector<ActorPlayer> actor_players_;
  /// Each actor's collisions as static shapes: (actor index, X_AS in the actor frame, shape).
  struct ActorShape {
    int actor = 0;
    Eigen::Isometry3d X_AS = Eigen::Isometry3d::Identity();
    int shape = -1;
  };
  std::vector<ActorShape> actor_shapes_;
  /// The same scripts for the physics, a step ahead of the sim time (a player replays from 0
  /// when asked for an earlier time, so each reader keeps its own).
  std::vector<ActorPlayer> actor_physics_players_;
  // After scene_ and caster_, which its sensors read; made in the constructor (its profile rows
  // after the Simulator's), reset first in ~Simulator.
  std::unique_ptr<SensorHost> sensors_;
  ContactTracker contacts_;
  std::vector<RobotContact> contact_scratch_;  // linkContacts
  Schedule reply_schedule_, tick_schedule_;
  bool lockstep_replies_ = false, lockstep_ticks_ = false;
  bool paused_ = false;
  std::unique_ptr<Properties> properties_;  // properties(); made in the constructor

  bool track_contacts_ = true;
  // options_.profile's rows
  int contacts_row_ = -1, step_row_ = -1, scene_row_ = -1;
};

}  // namespace tianracer_sim

#endif  // TIANRACER_SIM_SIMULATOR_SIMULATOR_H
