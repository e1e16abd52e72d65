// One robot in one world, made from the same files as the ROS node (a xacro or URDF, a
// ros_control YAML, a world) and driven without ROS: the core of the Python bindings and the
// Gymnasium environment (docs/learning.md). It owns a Simulator (simulator/simulator.h), adds
// the robot as the node does, computes only the outputs named in `observe`, and drives the
// controllers directly or through the cmd_vel node's Ackermann maths (ackermann_drive.h).
// ROS-free.
#ifndef TIANRACER_SIM_ENV_SIM_ENV_H
#define TIANRACER_SIM_ENV_SIM_ENV_H

#include <cstdint>
#include <functional>
#include <limits>
#include <memory>
#include <optional>
#include <stdexcept>
#include <string>
#include <vector>

#include <Eigen/Geometry>

#include "tianracer_sim/env/ackermann_drive.h"
#include "tianracer_sim/simulator/simulator.h"

namespace tianracer_sim {

/// A bad configuration or input of the environment; the message names the value.
class EnvError : public std::invalid_argument {
 public:
  using std::invalid_argument::invalid_argument;
};

struct EnvConfig {
  // The robot: a xacro (run with model_args, "name:=value") or URDF file, or URDF text.
  std::string model;
  std::vector<std::string> model_args;
  std::string urdf;
  std::string model_dir;   // relative mesh paths of `urdf` resolve here
  std::string robot_name;  // "" = the gazebo_ros_control namespace, else the URDF's name
  // Its controllers: a ros_control YAML ("" = none), the key they are under ("" = as the node
  // chooses it: the model's ros_control namespace, else the YAML's one key that defines
  // controllers) and which ones ([] = all). The node's rules (simulator/robot_setup.h).
  std::string control_config;
  std::string control_namespace;
  std::vector<std::string> controllers;
  // The world: a shipped name (worlds_dir/<name>.world), a .world path or a map .yaml.
  std::string world = "empty";
  std::string worlds_dir;  // "" = find_package("tianracer_sim") + "/worlds"
  // Spawn pose of base_link; drop_to_ground: z such that the model rests on z = 0.
  Eigen::Isometry3d X_WB = Eigen::Isometry3d::Identity();
  bool drop_to_ground = true;
  std::uint64_t seed = 0;      // sensors' noise
  double max_step_size = 0.0;  // physics step (s); 0 = the world's
  std::vector<std::string> disabled_sensors;
  /// What to compute (everything else is not): "odom" (ground truth as the node publishes it),
  /// "joints", a kind ("scan", "image", "depth", "imu", "ground_truth": the robot's one
  /// sensor of it), a sensor name (its main output), or "<sensor>/<output>" (a depth camera's
  /// "image" or "depth", a multicamera's camera index).
  std::vector<std::string> observe;
  /// package:// and $(find) lookups ("" when unknown); required.
  std::function<std::string(const std::string&)> find_package;
  /// Loaders' and sensors' warnings (may be empty).
  std::function<void(const std::string&)> warn;
  /// Measure thread CPU time spent in physics and sensors (timing()); costs two clock reads
  /// per physics step.
  bool timing = false;
};

/// One observation: what it holds, its numpy shape and type, and when its value was sampled.
struct Observation {
  enum class Kind { kScan, kImage, kDepth, kImu, kGroundTruth, kOdom, kJoints };
  std::string key;  // as named in `observe`
  Kind kind = Kind::kOdom;
  const SimSensor* sensor = nullptr;  // null for odom and joints
  SensorOutputs outputs = 0;          // the sensor's output bits it needs
  int camera = -1;                    // a multicamera's camera
  std::vector<std::size_t> shape;
  char dtype = 'd';  // numpy type char: 'f' float32, 'd' float64, 'B' uint8, 'H' uint16
  std::size_t itemsize = 8;
  /// Sim time the value was sampled at (a sensor holds its last sample between its samples);
  /// NaN before the first.
  double stamp = std::numeric_limits<double>::quiet_NaN();
  std::size_t bytes() const;
};

/// A controller with a command (the action of raw control): its joint and command range.
struct CommandSpec {
  std::string controller, joint, type;
  double lower = 0.0, upper = 0.0;  // from the URDF limits (position, velocity or effort)
};

/// CPU seconds on the stepping thread (EnvConfig::timing), and wall seconds waiting for
/// camera frames rendered on the frame worker.
struct EnvTiming {
  double physics = 0.0, sensors = 0.0, frames_wait = 0.0;
  std::uint64_t steps = 0;
};

class SimEnv {
 public:
  /// Loads everything and takes the initial observation (time 0). Throws EnvError for a bad
  /// configuration (naming it), and the loaders' errors (ModelError, WorldError,
  /// ControllerError, ...) naming file and value.
  explicit SimEnv(EnvConfig config);
  ~SimEnv();
  SimEnv(const SimEnv&) = delete;
  SimEnv& operator=(const SimEnv&) = delete;

  // --- what it is --------------------------------------------------------------------------
  const EnvConfig& config() const { return config_; }
  const std::vector<Observation>& observations() const { return observations_; }
  const std::vector<CommandSpec>& commands() const { return commands_; }
  /// The Ackermann drive; null when the model has none (ackermannProblem() says why).
  const AckermannDrive* ackermann() const { return drive_.get(); }
  const std::string& ackermannProblem() const { return drive_problem_; }
  const std::string& urdf() const { return urdf_; }
  const std::string& robotName() const { return robot_name_; }
  /// The robot's ros_control namespace and where its controllers were read, as the node has
  /// them (simulator/robot_setup.h): "/tianracer".
  const std::string& robotNamespace() const { return setup_ns_; }
  const std::string& controlNamespace() const { return control_ns_; }
  /// (name, type) of every controller, in load order (controller_manager's list_controllers).
  std::vector<std::pair<std::string, std::string>> controllers() const;
  /// Every sensor of the robot: name and kind (SensorKind id).
  std::vector<std::pair<std::string, std::string>> sensors() const;
  Simulator& simulator() { return *sim_; }
  const Simulator& simulator() const { return *sim_; }
  ModelId robot() const { return robot_; }

  // --- driving -----------------------------------------------------------------------------
  /// One value per commands() entry. Throws EnvError naming a non-finite value's controller
  /// (nothing is applied then).
  void setCommands(const double* values, std::size_t n);
  /// The cmd_vel node's Ackermann drive command (speed m/s, steering angle rad) at this time.
  /// Throws EnvError without a drive or for non-finite input.
  void setAckermann(double speed, double steering);
  /// n physics steps (controllers, physics, sensors that are due and observed), then the
  /// camera frames in flight complete. Returns the contacts begun during them.
  std::uint64_t step(int n);
  /// Time 0, controllers restarted, the robot at X_WB (resting on the ground when
  /// `rest_on_ground`: z from its lowest collision point) or at its spawn pose, and the
  /// initial observation taken.
  void reset(const std::optional<Eigen::Isometry3d>& X_WB = std::nullopt,
             bool rest_on_ground = true);
  /// A new simulation with this noise seed (what reset(seed=...) needs to repeat exactly):
  /// the model, controllers and world are reused. Call reset() next: its sample at time 0 is
  /// the sensors' first, as at the node's start.
  void reseed(std::uint64_t seed);

  // --- reading -----------------------------------------------------------------------------
  double time() const { return sim_->time(); }
  double dt() const { return sim_->dt(); }
  /// Writes observation i's current value (observations()[i].bytes() bytes) to `out`.
  void read(std::size_t i, void* out) const;
  /// Ground truth as the node's <ns>/ground_truth/odom: position, orientation (x, y, z, w) in
  /// the world; linear and angular velocity in base_link.
  void odom(double out[13]) const;
  void jointStates(JointStates* out) const { sim_->jointStates(robot_, out); }
  /// Contacts begun since the start (a wheel rolling on the ground is none).
  std::uint64_t contactCount() const { return sim_->contactCount(robot_); }
  /// The robot's contacts in the last physics step, one per touching pair.
  std::vector<LinkContact> contacts();
  const EnvTiming& timing() const { return timing_; }
  void clearTiming() { timing_ = EnvTiming(); }

 private:
  class Listener;
  void build(std::uint64_t seed);
  Observation resolve(const std::string& what) const;
  void stampState();  // odom and joints are read at the current time
  void senseInitial();  // the samples at time 0

  EnvConfig config_;
  std::string urdf_, robot_name_, setup_ns_, control_ns_;
  RobotModel model_;
  std::vector<tianracer_control::ControllerSpec> controller_specs_;
  WorldDescription world_;
  std::unique_ptr<Simulator> sim_;
  ModelId robot_ = kNoModel;
  std::vector<Observation> observations_;
  std::vector<CommandSpec> commands_;
  std::unique_ptr<AckermannDrive> drive_;
  std::string drive_problem_;
  EnvTiming timing_;
  bool initial_ = false;  // the samples at time 0 were taken
};

}  // namespace tianracer_sim

#endif  // TIANRACER_SIM_ENV_SIM_ENV_H
