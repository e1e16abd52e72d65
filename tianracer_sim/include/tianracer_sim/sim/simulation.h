// Simulation: the step loop without ROS (docs/simulator.md): robots from their RobotModel,
// their ros_control-style controllers from tianracer_control, the physics world, and sim time:
//   read joint state -> controllers update (every control period) -> write commands ->
//   physics step.
// Sensors and publishing are driven by the host (the ROS node) from the state after a step.
#ifndef TIANRACER_SIM_SIM_SIMULATION_H
#define TIANRACER_SIM_SIM_SIMULATION_H

#include <memory>
#include <optional>
#include <string>
#include <vector>

#include <Eigen/Geometry>

#include <tianracer_control/joint_controllers.h>
#include <tianracer_control/joint_handle.h>

#include "tianracer_sim/common/step_profile.h"
#include "tianracer_sim/sim/controller_manager.h"
#include "tianracer_sim/sim/robot_hw_sim.h"
#include "tianracer_sim/sim/steer_bot_hw_sim.h"
#include "tianracer_sim/model/robot_model.h"
#include "tianracer_sim/physics/world.h"

namespace tianracer_sim {

/// A robot to add: its model, where it spawns, and the controllers to start.
struct RobotConfig {
  std::string name;  // unique in the world, e.g. "tianracer"
  RobotModel model;
  Eigen::Isometry3d X_WB_spawn = Eigen::Isometry3d::Identity();
  /// Replace the spawn height so that the lowest collision point (joints at 0) rests on z = 0.
  bool drop_to_ground = false;
  std::vector<tianracer_control::ControllerSpec> controllers;
  /// gazebo_ros_control's joint_limits and pid_gains parameters (sim/robot_hw_sim.h).
  RobotHwSimParams hw_sim;
};

/// One robot of the simulation with its hardware interface and controllers.
struct SimRobot {
  std::string name;
  RobotId id = -1;
  RobotModel model;
  /// One handle per transmission joint, in transmission order. Stable storage: controllers
  /// keep pointers into it.
  std::vector<tianracer_control::JointHandle> handles;
  std::vector<int> handle_joint;  // PhysicsRobot joint index of each handle (-1: none)
  std::vector<bool> claimed;      // handle written by a controller (others stay free)
  tianracer_control::ControllerSet controllers;
  int control_every = 1;  // controllers run every control_every physics steps
  /// DefaultRobotHWSim between the handles and the joints: limits, PID gains, e-stop.
  RobotHwSim hw_sim;
  /// <robotSimType> steer_bot_hardware_gazebo/SteerBotHardwareGazebo: in place of hw_sim, its
  /// handles (not the transmissions') fanned out onto the joints.
  std::optional<SteerBotHwSim> steer_bot;
};

class Simulation {
 public:
  explicit Simulation(const PhysicsOptions& options = PhysicsOptions(),
                      WarningSink warn = WarningSink());

  /// Adds the robot to the physics world and starts its controllers. Throws ModelError,
  /// PhysicsError, MeshError or tianracer_control::ControllerError (messages name the robot,
  /// joint or controller); on a throw nothing of the robot is kept.
  SimRobot& addRobot(RobotConfig config);
  /// Takes the robot out (delete_model): its controllers stop and its bodies leave the
  /// physics world; SimRobot references to it become invalid. Throws ModelError for an
  /// unknown name.
  void removeRobot(const std::string& name);

  /// The robots' controllers: loaded with a robot, loaded, unloaded and switched by name,
  /// run every control period (sim/controller_manager.h).
  ControllerManager& controllerManager() { return controllers_; }

  /// One physics step of dt.
  void step();
  /// A new physics step from the next step on (PhysicsWorld::setTimeStep); controllers with a
  /// controlPeriod keep it as nearly as the new step allows. Throws PhysicsError.
  void setTimeStep(double dt);

  /// /gazebo/reset_simulation: time to 0, robots to spawn, controllers reset.
  void resetSimulation();
  /// /gazebo/reset_world: robots to spawn, controllers reset, the world's free bodies to their
  /// initial poses; time keeps running.
  void resetWorld();

  double time() const { return physics_.time(); }
  double dt() const { return physics_.dt(); }
  std::uint64_t stepCount() const { return physics_.stepCount(); }

  PhysicsWorld& physics() { return physics_; }
  const PhysicsWorld& physics() const { return physics_; }
  std::vector<std::unique_ptr<SimRobot>>& robots() { return robots_; }
  /// step() times its controllers and its physics step into `profile` (null: not timed; it
  /// must outlive the simulation).
  void setProfile(StepProfile* profile);
  SimRobot* findRobot(const std::string& name);
  /// A robot or a free body of the world (a dynamic model) by name; null when none.
  const PhysicsRobot* findModel(const std::string& name) const;

 private:
  void read(SimRobot& robot);
  void write(SimRobot& robot);
  void restartControllers(SimRobot& robot);

  PhysicsWorld physics_;
  WarningSink warn_;
  ControllerManager controllers_;
  std::vector<std::unique_ptr<SimRobot>> robots_;
  StepProfile* profile_ = nullptr;
  int controllers_row_ = -1, bullet_row_ = -1;
};

/// Builds the hardware interface of a robot: one JointHandle per transmission, its interface
/// the transmission's first joint interface, limits from the physics joint. Throws ModelError
/// for a transmission whose joint is not a movable joint of the robot.
void buildJointHandles(const RobotModel& model, const PhysicsRobot& robot,
                       std::vector<tianracer_control::JointHandle>* handles,
                       std::vector<int>* handle_joint);

/// Height of the lowest collision point of the robot below its base_link origin, with all joints
/// at 0 and the base rotated by R_WB (positive when the geometry reaches below the base).
/// Exact for boxes, spheres and cylinders; meshes by their vertices.
double depthBelowBase(const RobotModel& model, const Eigen::Matrix3d& R_WB);

/// Bounds of a base state set from outside (spawn, set_model_state): beyond them the physics and
/// the ray caster lose all precision (Embree refuses ray origins beyond about 1.8e18 and aborts).
constexpr double kMaxModelPosition = 1e6;         // m, each coordinate
constexpr double kMaxModelLinearVelocity = 1e3;   // m/s, each component
constexpr double kMaxModelAngularVelocity = 1e4;  // rad/s, each component

/// "" when the base pose and twist are finite and within the bounds above, else what is wrong,
/// e.g. "position x 1e+30 is out of range (|x| <= 1e+06 m)".
std::string checkModelState(const Eigen::Isometry3d& X_WB, const Twist& V_WB);

}  // namespace tianracer_sim

#endif  // TIANRACER_SIM_SIM_SIMULATION_H
