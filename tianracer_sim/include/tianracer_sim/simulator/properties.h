// What gazebo_ros's property services read and change (gazebo_ros/src/gazebo_ros_api_plugin.cpp:
// get/set_physics_properties, get/set_joint_properties, set_model_configuration,
// get_link_properties, get/set_light_properties, delete_light), without ROS. The Simulator
// owns one and hands it out (Simulator::properties()); it finds models, links and joints
// through the one name resolver (simulator/entities.h). A new property service touches this
// class and its ROS file (ros/gazebo_properties.cpp), not the Simulator. Calls between steps
// only, as the Simulator's.
#ifndef TIANRACER_SIM_SIMULATOR_PROPERTIES_H
#define TIANRACER_SIM_SIMULATOR_PROPERTIES_H

#include <functional>
#include <optional>
#include <string>
#include <vector>

#include <Eigen/Geometry>

#include "tianracer_sim/physics/world.h"
#include "tianracer_sim/scene/scene.h"
#include "tianracer_sim/world/world.h"

namespace tianracer_sim {

class Simulation;
class Simulator;

/// The physics settings gazebo_ros's get/set_physics_properties read and change.
struct PhysicsProperties {
  double time_step = 0.0;        // s
  /// Steps per wall-clock second the run loop aims at (Gazebo's real_time_update_rate; the
  /// real-time factor is max_update_rate * time_step); 0 = as fast as possible.
  double max_update_rate = 0.0;
  Eigen::Vector3d gravity = Eigen::Vector3d::Zero();
  int solver_iterations = 0;                // ODE's "iters"
  double contact_max_correcting_vel = 0.0;  // m/s
  /// Read only: free bodies may sleep (PhysicsOptions::sleep_time > 0), Gazebo's
  /// auto_disable_bodies; and the solver's other settings.
  bool auto_disable_bodies = false;
  SolverSettings solver;
};

/// A movable joint as get_joint_properties reports it.
struct JointProperties {
  std::string model;  // the model (robot or world model) it belongs to
  JointInfo info;     // type, limits, damping, friction (current values)
  double position = 0.0, rate = 0.0;
};

/// What set_joint_properties changes (unset: unchanged).
struct JointPropertiesChange {
  std::optional<double> damping, lower, upper, friction;
  /// A velocity target driven with at most fmax (ODE's "vel" and "fmax"); both or neither.
  std::optional<double> velocity, fmax;
};

/// A link's inertial as get_link_properties reports it: mass, centre of mass in the link
/// frame, inertia about it (in the link frame's axes for robots, the <inertial> frame's for
/// world models, as Gazebo).
struct LinkProperties {
  double mass = 0.0;
  Eigen::Vector3d com = Eigen::Vector3d::Zero();
  Eigen::Matrix3d inertia = Eigen::Matrix3d::Zero();
  bool gravity_mode = true;
};

/// What set_light_properties changes.
struct LightChange {
  Eigen::Vector4f diffuse{0.8f, 0.8f, 0.8f, 1.0f};
  Eigen::Vector4f specular{0.2f, 0.2f, 0.2f, 1.0f};
  Attenuation attenuation;
  Eigen::Vector3d direction = Eigen::Vector3d::Zero();  // zero: unchanged
};

/// The physics step (s) the world's <physics> asks for (<max_step_size>), what a Simulator
/// built with SimulatorOptions::max_step_size 0 steps with.
double worldTimeStep(const WorldDescription& world);

class Properties {
 public:
  /// Parts of the Simulator `sim` that owns it: its simulation, its scene (the lights), and
  /// `scene_moved`, called when links moved between steps (the scene's poses are stale).
  /// `max_update_rate` is the run loop's pace to start with.
  Properties(Simulator& sim, Simulation& simulation, Scene& scene,
             std::function<void()> scene_moved, double max_update_rate);

  // Each setter checks everything first and throws InputError naming the entity, the field and
  // the value; nothing changes then.
  PhysicsProperties physicsProperties() const;
  /// time_step (from the next step; controllers keep their periods), max_update_rate (>= 0),
  /// gravity, solver_iterations, contact_max_correcting_vel. auto_disable_bodies cannot be
  /// changed: a different value is refused.
  void setPhysicsProperties(const PhysicsProperties& p);
  double maxUpdateRate() const { return max_update_rate_; }
  /// A movable joint by "joint" (the first model that has one of that name: the world's
  /// models, then the robots, as Gazebo searches its models) or "model::joint". Fixed joints
  /// are merged away (robots, as Gazebo's URDF import; world models: one body) and not found.
  /// Throws InputError naming the joint.
  JointProperties jointProperties(const std::string& joint) const;
  void setJointProperties(const std::string& joint, const JointPropertiesChange& change);
  /// gazebo's Model::SetJointPositions (set_model_configuration): the named joints of a robot
  /// or moving world model to the positions, their rates to 0; the base stays. Names and
  /// positions of equal length, every name a movable joint of the model, positions finite.
  void setModelConfiguration(const std::string& model, const std::vector<std::string>& joints,
                             const std::vector<double>& positions);
  /// "model::link": a robot's link that is a body of its own (a link lumped into its parent by
  /// a fixed joint is not found, as in Gazebo), or any link of a world model.
  LinkProperties linkProperties(const std::string& link) const;
  /// The world's lights (the sun first when the world includes it), as drawn.
  const std::vector<DirectionalLight>& lights() const { return scene_.lights; }
  /// Colours and attenuation of light `name` (colours finite and >= 0, attenuation finite and
  /// >= 0, a direction finite); cameras draw it from the next frame.
  void setLight(const std::string& name, const LightChange& change);
  /// Takes the light out of the scene (delete_light).
  void deleteLight(const std::string& name);

 private:
  Simulator& sim_;            // the name resolver (entities()) and waitFrames()
  Simulation& simulation_;    // the physics' settings
  Scene& scene_;              // the lights
  std::function<void()> scene_moved_;
  double max_update_rate_ = 0.0;
};

}  // namespace tianracer_sim

#endif  // TIANRACER_SIM_SIMULATOR_PROPERTIES_H
