// The simulator's ROS node: parameters in, Simulation stepped, Gazebo's topics and services
// out. Thin: the physics, controllers and sensors are the ROS-free libraries.
//
// Parameters (private, ~):
//   world            a shipped world (empty, walled_room, racetrack) or a .world path
//   robots           names of several robots to spawn (list or space-separated string); each
//                    robot's parameters below (model ... disable_sensors, control_namespace)
//                    are then read from ~<name>/ and its robot_name is <name>. Unset: one
//                    robot from the parameters in ~ itself.
//   model            xacro/URDF file; when empty, the URDF is read from robot_param
//   model_dir        folder that relative mesh URIs of robot_param's URDF resolve against
//                    (sim.launch sets it to the model file's folder)
//   robot_param      parameter holding the URDF (default: the gazebo_ros_control plugin's
//                    robotParam, else "robot_description"), resolved in the robot namespace's
//                    parent like gazebo_ros_control does (i.e. /robot_description)
//   robot_name       model name (default: the plugin's robotNamespace without '/', else the
//                    URDF's robot name)
//   x, y, z, roll, pitch, yaw   spawn pose of base_link; z "auto" (default) drops the robot
//                    so that its lowest collision point touches z = 0
//   controllers      names to start (list or space-separated string); default every
//                    controller defined under the robot's ros_control namespace
//   real_time_factor 1.0 = real time, 0 = as fast as possible (default: the world's)
//   paused           start paused
//   max_step_size    physics step (s), default the world's <max_step_size>
//   clock_rate       /clock messages per sim second (0 = every step; default 200)
//   ground_truth_rate  <ns>/ground_truth/odom rate (Hz, default 50)
//   gazebo_states_rate /gazebo/model_states and link_states rate (Hz, default 50; 0 = every step)
//   seed             seed of the sensors' noise (default 0): same seed, same noise
//   odom_frame       static TF world -> <odom_frame> at the spawn pose (default odom; "" = none)
//   disable_sensors  sensor types (ray, camera, depth) or names to leave out (list or string)
//   control_namespace  where the controllers' parameters are read (default: the ros_control
//                    namespace, e.g. /tianracer); command topics stay in the ros_control namespace
// Frames: a `tf_prefix` parameter found from the robot's ros_control namespace (searchParam,
// as robot_state_publisher and gazebo_ros plugins do) prefixes every frame published for
// the robot: sensor frames, optical frames, ground truth's child frame and the odom frame.
//   status_period    wall seconds between status lines and /diagnostics (default 5; 0 = off)
// Robots spawned at run time (/gazebo/spawn_urdf_model) read controllers, control_namespace,
// odom_frame, disable_sensors and model_dir from ~<model name>/, as robots listed in ~robots;
// without ~<name>/controllers or ~<name>/control_namespace they start no controller (as in
// Gazebo: a spawner starts them through <ns>/controller_manager/, served for every robot with
// gazebo_ros_control).
// Start-up and spawn build robots through the same addRobot().
#ifndef TIANRACER_SIM_ROS_SIM_NODE_H
#define TIANRACER_SIM_ROS_SIM_NODE_H

#include <map>
#include <memory>
#include <string>
#include <vector>

#include <ros/callback_queue.h>
#include <ros/ros.h>
#include <sensor_msgs/JointState.h>
#include <tf2_ros/static_transform_broadcaster.h>
#include <std_srvs/Empty.h>

#include <tianracer_control/ros/controller_adapter.h>

#include "tianracer_sim/lidar/ray_caster.h"
#include "tianracer_sim/render/renderer.h"
#include "tianracer_sim/ros/borrowed_msgs.h"
#include "tianracer_sim/ros/contact_publisher.h"
#include "tianracer_sim/ros/controller_manager_bridge.h"
#include "tianracer_sim/ros/gazebo_interface.h"
#include "tianracer_sim/ros/lockstep.h"
#include "tianracer_sim/ros/sensors/sensor_publisher.h"
#include "tianracer_sim/scene/scene.h"
#include "tianracer_sim/sim/frame_worker.h"
#include "tianracer_sim/sim/robot_scene.h"
#include "tianracer_sim/sim/simulation.h"
#include "tianracer_sim/sim/world_physics.h"
#include "tianracer_sim/world/world.h"

namespace tianracer_sim {

class SimNode : private SensorHost, private ModelSpawner {
 public:
  /// Reads parameters, loads the robot and starts its controllers. Throws std::exception with
  /// a message naming the parameter, file or controller on a configuration error.
  SimNode(const ros::NodeHandle& nh, const ros::NodeHandle& pnh);
  ~SimNode();

  /// Steps until ros::ok() is false.
  void run();

 private:
  struct JointStateStream {
    ros::Publisher pub;
    std::vector<int> joints;  // PhysicsRobot joint indices
    Schedule schedule;
    sensor_msgs::JointState msg;
  };
  /// One robot of the node; robot == nullptr once deleted (delete_model), so that the
  /// indices sensors hold stay valid.
  struct RobotIo {
    SimRobot* robot = nullptr;
    std::string ns;  // ros_control namespace, e.g. "/tianracer"
    std::shared_ptr<tianracer_control::ControllerCommandSubscribers> commands;
    std::string control_ns;  // where its controllers' parameters are read
    std::unique_ptr<ControllerManagerBridge> controller_manager;  // with gazebo_ros_control
    std::vector<JointStateStream> joint_states;
    RobotSceneBodies scene_bodies;
    ros::Publisher ground_truth;
    Schedule ground_truth_schedule;
    std::string tf_prefix;  // "" for a robot alone; e.g. "tianracer_02"
    std::string base_frame;  // tf_prefix + root link
    std::vector<std::string> topics;  // sensor topics it claimed (topic_owner_)
    std::vector<std::size_t> stats;   // its sensors' entries of stats_
  };

  /// A robot to add, however it came: from the node's parameters at start-up or from
  /// spawn_urdf_model at run time. Both go through addRobot().
  struct RobotRequest {
    RobotModel model;
    std::string name;
    Eigen::Isometry3d X_WB = Eigen::Isometry3d::Identity();
    bool auto_z = false;  // drop to the ground (z "auto")
    /// The robot's own parameters: controllers, control_namespace, odom_frame,
    /// disable_sensors (~ for one robot, ~<name>/ for several or spawned ones).
    ros::NodeHandle rp;
    /// Through spawn_urdf_model: no controller starts unless ~<name>/ names them (in Gazebo a
    /// spawner starts them).
    bool spawned = false;
  };

  /// The frames due at one step: rendered and published on camera_worker_'s thread from
  /// render_scene_, a snapshot of scene_ at that step.
  struct FrameJob {
    ros::Time stamp;
    std::vector<FrameRequest> frames;
  };

  /// Logs each distinct warning once (loaders repeat theirs for every robot and spawn).
  static void warnOnce(const std::string& text);
  /// Loads one robot from the parameters in `rp`; `name` fixes its name (else ~robot_name).
  void loadRobot(const ros::NodeHandle& rp, const std::string& name);
  /// Adds the robot with its controllers, topics and sensors. Throws on bad input (a
  /// message naming the robot); nothing of the robot stays then.
  void addRobot(RobotRequest request);
  /// The rest of addRobot once the robot is in the simulation: scene, frames, topics,
  /// contacts, sensors.
  void setUpRobotIo(std::size_t index, const ros::NodeHandle& rp);
  // In sim_node_spawn.cpp: models at run time.
  /// Everything of robots_[index] out: topics, sensors, scene, physics.
  void removeRobotAt(std::size_t index);
  // ModelSpawner: spawn_urdf_model, spawn_sdf_model and delete_model, between steps.
  void spawnRobot(const std::string& name, const std::string& urdf,
                  const Eigen::Isometry3d& X_WB) override;
  void spawnWorldModel(const std::string& name, const std::string& sdf,
                       const Eigen::Isometry3d& X_WM) override;
  void deleteModel(const std::string& name) override;
  /// Advertises `topic` for a robot's sensor; throws when another sensor publishes there.
  void claimTopic(const std::string& topic, const std::string& owner);
  bool ensureRenderer();
  /// Hands the frames requested at this step to the frame worker.
  void submitFrames(const ros::Time& stamp);
  void publishStatus();
  void setUpSensors(size_t robot_index, const ros::NodeHandle& rp);
  /// One sensor (or sensor-like model plugin) through the registry; a bad one is left out.
  void setUpSensor(size_t robot_index, const SensorSpec& spec);
  /// Brings the scene's robot bodies to the current physics poses, once per step.
  void updateScene();
  void setUpJointStates(RobotIo& io);
  /// After controller_manager changed a robot's controllers: command topics and joint_states.
  void refreshControllerIo(std::size_t index);
  void stepOnce();
  /// Publishes what is due at this step; `clock` false leaves /clock to the caller (lockstep).
  void publishDue(bool clock = true);
  void publishClock();
  void restartSchedules();

  // SensorHost: what sensor publishers use at a step.
  const Scene& scene() override;
  RayCaster& caster() override { return caster_; }
  Eigen::Isometry3d linkPose(std::size_t robot, const std::string& link) const override;
  bool linkState(std::size_t robot, const std::string& link, LinkState* state) const override;
  void requestFrame(const FrameRequest& request) override { due_frames_.frames.push_back(request); }
  void linkContacts(std::size_t robot, const std::string& link,
                    std::vector<BumperContact>* out) override;
  SensorStat& stat(std::size_t index) override { return stats_[index]; }

  bool onPause(std_srvs::Empty::Request&, std_srvs::Empty::Response&);
  bool onUnpause(std_srvs::Empty::Request&, std_srvs::Empty::Response&);
  bool onResetSimulation(std_srvs::Empty::Request&, std_srvs::Empty::Response&);
  bool onResetWorld(std_srvs::Empty::Request&, std_srvs::Empty::Response&);

  ros::NodeHandle nh_, pnh_;
  ros::CallbackQueue queue_;  // commands and services run between steps, in this thread
  std::unique_ptr<WorldDescription> world_;
  WorldLoadOptions world_options_;
  /// What each model of world_ put into the physics (delete_model takes it out again).
  std::map<std::string, WorldModelBodies> world_bodies_;
  std::unique_ptr<Simulation> sim_;
  Scene scene_;  // what sensors see: the world's models and every robot's links
  std::uint64_t scene_step_ = ~0ull;  // step count the scene's poses belong to
  RayCaster caster_;
  std::unique_ptr<Renderer> renderer_;
  bool renderer_failed_ = false;
  // After renderer_: camera sensors render through it and go first.
  std::vector<std::unique_ptr<SensorPublisher>> sensors_;
  std::vector<std::size_t> sensor_robot_;  // robots_ index of each of sensors_
  std::map<std::string, int> sensors_of_kind_;  // SensorKind id -> sensors set up
  std::map<std::string, std::string> left_out_;  // the robot being loaded: sensor -> why left out
  tf2_ros::StaticTransformBroadcaster static_tf_;
  std::vector<SensorStat> stats_;  // one per sensor, in set-up order
  ros::Publisher diagnostics_pub_;
  double status_period_ = 5.0;  // wall seconds between status reports
  ros::WallTime status_wall_;
  double status_sim_ = 0.0;
  std::uint64_t seed_ = 0;
  std::vector<RobotIo> robots_;
  std::unique_ptr<ContactPublisher> contacts_;  // robots' contacts and their counts
  std::vector<RobotContact> contact_scratch_;   // for linkContacts
  std::map<std::string, std::string> topic_owner_;  // sensor topics: who publishes there

  ros::Publisher clock_pub_;
  Schedule clock_schedule_;
  double ground_truth_rate_ = 50.0;
  double real_time_factor_ = 1.0;
  bool paused_ = false;
  bool pacing_reset_ = true;
  std::vector<ros::ServiceServer> services_;
  std::unique_ptr<Lockstep> lockstep_;  // null unless ~lockstep/ names topics
  std::unique_ptr<GazeboInterface> gazebo_;  // gazebo_msgs topics and services

  FrameJob due_frames_;  // filled each step, handed to the worker (capacity kept)
  Scene render_scene_;    // the worker's snapshot of scene_
  // Started with the first frame; reset first in ~SimNode (it uses the sensors above).
  std::unique_ptr<FrameWorker<FrameJob>> camera_worker_;
};

}  // namespace tianracer_sim

#endif  // TIANRACER_SIM_ROS_SIM_NODE_H
