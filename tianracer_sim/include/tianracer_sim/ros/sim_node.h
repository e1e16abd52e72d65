// The simulator's ROS node: parameters in, the ROS-free Simulator (simulator/simulator.h)
// stepped, Gazebo's topics and services out. Bridges only: RobotBridge (commands, joint_states,
// ground truth, odom TF), the sensor publishers (ros/plugins/), GazeboInterface (world state,
// spawn, pause and reset), Lockstep, /clock and the status.
//
// Parameters (private, ~):
//   world            a shipped world (empty, walled_room, racetrack) or a .world path
//   robots           names of several robots to spawn (list or space-separated string); each
//                    robot's parameters below (model ... disable_sensors, control_namespace)
//                    are then read from ~<name>/ and its robot_name is <name>. Unset: one
//                    robot from the parameters in ~ itself. Empty ([] or ""): the world
//                    alone, as `gzserver x.world`; robots arrive through spawn_urdf_model.
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
//   enable_ros_network gazebo_ros's: false = no /gazebo topics or services (default true)
//   gazebo_namespace where the Gazebo topics and services are (default /gazebo; gazebo_ros's
//                    gzserver: its node's own name, as gazebo_ros_api_plugin's "~")
//   step_services    ~step and ~step_and_wait (default true; gazebo_ros's gzserver: false)
//   diagnostics      publish /diagnostics (default true; gazebo_ros's gzserver: false)
//   seed             seed of the sensors' noise (default 0): same seed, same noise
//   odom_frame       static TF world -> <odom_frame> at the spawn pose (default odom; "" = none)
//   disable_sensors  sensor types (ray, camera, depth) or names to leave out (list or string)
//   control_namespace  where the controllers' parameters are read (default: the ros_control
//                    namespace, e.g. /tianracer); command topics stay in the ros_control namespace
// Frames: a `tf_prefix` parameter found from the robot's ros_control namespace (searchParam,
// as robot_state_publisher and gazebo_ros plugins do) prefixes every frame published for
// the robot: sensor frames, optical frames, ground truth's child frame and the odom frame.
//   status_period    wall seconds between status lines and /diagnostics (default 5; 0 = off)
//   profile          time each part of the step (default false): the service ~profile
//                    (std_srvs/Trigger) answers the table (docs/performance.md), which also
//                    is printed on stdout at exit
// Robots spawned at run time (/gazebo/spawn_urdf_model) read controllers, control_namespace,
// odom_frame, disable_sensors and model_dir from ~<model name>/, as robots listed in ~robots;
// without ~<name>/controllers or ~<name>/control_namespace they start no controller (as in
// Gazebo: a spawner starts them through <ns>/controller_manager/, served for every robot with
// gazebo_ros_control).
// Start-up and spawn build robots through the same addRobot().
#ifndef TIANRACER_SIM_ROS_SIM_NODE_H
#define TIANRACER_SIM_ROS_SIM_NODE_H

#include <chrono>
#include <map>
#include <memory>
#include <string>
#include <vector>

#include <ros/callback_queue.h>
#include <ros/ros.h>
#include <tf2_ros/static_transform_broadcaster.h>

#include "tianracer_sim/common/pacer.h"
#include "tianracer_sim/ros/contact_publisher.h"
#include "tianracer_sim/ros/gazebo_interface.h"
#include "tianracer_sim/ros/lockstep.h"
#include "tianracer_sim/ros/robot_bridge.h"
#include "tianracer_sim/ros/sim_node_core.h"
#include "tianracer_sim/ros/step_bridge.h"
#include "tianracer_sim/simulator/robot_setup.h"
#include "tianracer_sim/simulator/simulator.h"

namespace tianracer_sim {

class SimNode : private ModelSpawner {
 public:
  /// Runs `core` (its Simulator built outside, ros/sim_node_core.h: makeSimNodeCore reads the
  /// world parameters): reads the robots' parameters, loads the robots and starts their
  /// controllers, offers Gazebo's topics and services. Throws std::exception with a message
  /// naming the parameter, file or controller on a configuration error.
  SimNode(const ros::NodeHandle& nh, const ros::NodeHandle& pnh, SimNodeCore core);
  ~SimNode();

  /// Steps until ros::ok() is false.
  void run();

 private:
  /// Logs each distinct warning once (loaders repeat theirs for every robot and spawn).
  static void warnOnce(const std::string& text);
  // In sim_node_robots.cpp: robots from parameters (start-up) or spawn_urdf_model, both through
  // addRobot(); delete_model.
  /// Loads one robot from the parameters in `rp`; `name` fixes its name (else ~robot_name).
  void loadRobot(const ros::NodeHandle& rp, const std::string& name);
  /// The one robot set-up (simulator/robot_setup.h) on the parameter server, from `rp`: the
  /// robot's own parameters (robot_name, controllers, control_namespace, control_config); its
  /// notes and warnings logged. `spawn_name`: spawn_urdf_model's name (`spawned`: no
  /// controller unless `rp` names them), or a robot of ~robots.
  RobotSetup setUpRobot(const RobotModel& model, const std::string& spawn_name, bool spawned,
                        const ros::NodeHandle& rp);
  /// The robot into the simulator with its bridges (`rp`: odom_frame, disable_sensors). Throws
  /// naming the robot; nothing of it stays then.
  void addRobot(RobotModel model, const RobotSetup& setup, const Eigen::Isometry3d& X_WB,
                bool auto_z, const ros::NodeHandle& rp);
  // ModelSpawner: spawn_urdf_model, spawn_sdf_model and delete_model, between steps.
  void spawnRobot(const std::string& name, const std::string& urdf,
                  const Eigen::Isometry3d& X_WB) override;
  void spawnWorldModel(const std::string& name, const std::string& sdf,
                       const Eigen::Isometry3d& X_WM) override;
  void deleteModel(const std::string& name) override;
  /// Lockstep's "commands" follow the controllers of every robot (added, deleted, loaded and
  /// unloaded through controller_manager).
  void updateCommandTopics();
  /// Advertises `topic` for a robot's sensor; throws when another sensor publishes there.
  void claimTopic(const std::string& topic, const std::string& owner);
  /// The publisher of a world model's sensor (Simulator::attachWorldSensors): the same
  /// as a robot's sensor of its kind, without tf_prefix; a camera's optical frame hangs from
  /// its frameName.
  void attachWorldSensor(SimSensor& sensor);

  void stepOnce();
  /// Publishes what is due at this step; `clock` false leaves /clock to the caller (lockstep).
  void publishDue(bool clock = true);
  void publishClock();
  /// Started paused, the data of the start time go out at the first step (unpause or ~step),
  /// so that what connects while it is paused gets them too.
  void publishInitial();
  void publishStatus();  // sim_node_status.cpp
  /// ~profile: the node's rows of the StepProfile given with the core and the ~profile service
  /// (sim_node_status.cpp).
  void setUpProfile();
  /// Start-up: the wall time since the last mark goes to `what` (until the start-up line is
  /// logged; spawns later are not start-up). sim_node_status.cpp.
  void startupMark(const std::string& what);
  void logStartup();

  /// After reset_simulation (GazeboInterface): the node's schedules restart, /clock goes back.
  void afterReset();

  ros::NodeHandle nh_, pnh_;
  ros::CallbackQueue queue_;  // commands and services run between steps, in this thread
  std::unique_ptr<StepProfile> profile_;  // ~profile; null when not profiling
  NodeProfileRows rows_;
  ros::ServiceServer profile_service_;
  std::chrono::steady_clock::time_point startup_last_ = std::chrono::steady_clock::now();
  std::vector<std::pair<std::string, double>> startup_;  // (what, ms); cleared once logged
  bool startup_logged_ = false;
  ros::NodeHandle root_;      // "/" on queue_
  WorldLoadOptions world_options_;
  std::unique_ptr<Simulator> sim_;
  /// Made with the first robot: /tf_static is advertised only once something is sent on it
  /// (a world alone offers gazebo_ros's topics only).
  std::unique_ptr<tf2_ros::StaticTransformBroadcaster> static_tf_;
  tf2_ros::StaticTransformBroadcaster& staticTf();
  std::vector<std::unique_ptr<RobotBridge>> robots_;  // in the order they were added
  std::map<std::string, std::string> topic_owner_;    // sensor topics: who publishes there
  std::map<std::string, std::vector<std::string>> world_model_topics_;  // by world model name
  std::unique_ptr<ContactPublisher> contacts_;        // robots' contacts on their topics
  ros::Publisher clock_pub_, diagnostics_pub_;
  int diagnostics_readers_ = 0;  // /diagnostics subscribers (its connect callbacks)
  Schedule clock_schedule_;
  double ground_truth_rate_ = 50.0;
  double real_time_factor_ = 1.0;
  Pacer pacer_;  // real_time_factor_ x real time
  double status_period_ = 5.0;  // wall seconds between status reports
  ros::WallTime status_wall_;
  double status_sim_ = 0.0;
  std::unique_ptr<Lockstep> lockstep_;       // null unless ~lockstep/ names topics
  std::unique_ptr<GazeboInterface> gazebo_;  // gazebo_msgs topics and services
  std::unique_ptr<StepBridge> step_;         // ~step and ~step_and_wait
  bool initial_published_ = false;
  double clock_published_ = -1.0;  // sim time of the last /clock
};

}  // namespace tianracer_sim

#endif  // TIANRACER_SIM_ROS_SIM_NODE_H
