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
//   seed             seed of the sensors' noise (default 0): same seed, same noise
//   odom_frame       static TF world -> <odom_frame> at the spawn pose (default odom; "" = none)
//   disable_sensors  sensor types (ray, camera, depth) or names to leave out (list or string)
//   control_namespace  where the controllers' parameters are read (default: the ros_control
//                    namespace, e.g. /tianracer); command topics stay in the ros_control namespace
// Frames: a `tf_prefix` parameter found from the robot's ros_control namespace (searchParam,
// as robot_state_publisher and gazebo_ros plugins do) prefixes every frame published for
// the robot: sensor frames, optical frames, ground truth's child frame and the odom frame.
//   status_period    wall seconds between status lines and /diagnostics (default 5; 0 = off)
#ifndef TIANRACER_SIM_ROS_SIM_NODE_H
#define TIANRACER_SIM_ROS_SIM_NODE_H

#include <map>
#include <memory>
#include <string>
#include <vector>

#include <ros/callback_queue.h>
#include <ros/ros.h>
#include <sensor_msgs/JointState.h>
#include <sensor_msgs/CameraInfo.h>
#include <sensor_msgs/Image.h>
#include <sensor_msgs/LaserScan.h>
#include <sensor_msgs/PointCloud2.h>
#include <tf2_ros/static_transform_broadcaster.h>
#include <std_srvs/Empty.h>

#include <tianracer_control/ros/controller_adapter.h>

#include "tianracer_sim/GetModelState.h"
#include "tianracer_sim/SetModelState.h"
#include "tianracer_sim/lidar/ray_caster.h"
#include "tianracer_sim/lidar/ray_sensor.h"
#include "tianracer_sim/render/camera_sensor.h"
#include "tianracer_sim/render/renderer.h"
#include "tianracer_sim/ros/borrowed_msgs.h"
#include "tianracer_sim/ros/contact_publisher.h"
#include "tianracer_sim/scene/scene.h"
#include "tianracer_sim/sim/frame_worker.h"
#include "tianracer_sim/sim/robot_scene.h"
#include "tianracer_sim/sim/simulation.h"
#include "tianracer_sim/world/world.h"

namespace tianracer_sim {

/// Something published on a sim-time schedule: due when time >= next; next advances by
/// period (a reset restarts it; a long pause does not cause a burst).
struct Schedule {
  double period = 0.0;  // s; 0 = every step
  double next = 0.0;
  bool due(double t);
  void restart(double t) { next = t; }
};

class SimNode {
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
  struct RobotIo {
    SimRobot* robot = nullptr;
    std::string ns;  // ros_control namespace, e.g. "/tianracer"
    std::shared_ptr<tianracer_control::ControllerCommandSubscribers> commands;
    std::vector<JointStateStream> joint_states;
    RobotSceneBodies scene_bodies;
    ros::Publisher ground_truth;
    Schedule ground_truth_schedule;
    std::string tf_prefix;  // "" for a robot alone; e.g. "tianracer_02"
    std::string base_frame;  // tf_prefix + root link
  };

  /// A lidar of a robot: published at its rate while someone subscribes.
  struct LidarIo {
    size_t robot = 0;  // index into robots_
    std::unique_ptr<RaySensor> sensor;
    int own_body = -1;  // scene body of the sensor's link: rays pass through its housing
    ros::Publisher pub;
    Schedule schedule;
    sensor_msgs::LaserScan msg;
    size_t stat = 0;  // index into stats_
  };

  /// A camera (libgazebo_ros_camera): image + camera_info.
  struct CameraIo {
    size_t robot = 0;
    std::unique_ptr<CameraSensor> sensor;
    ros::Publisher image, info;
    Schedule schedule;
    BorrowedImage image_msg;  // the sensor's buffer, serialised by publish() without a copy
    sensor_msgs::CameraInfo info_msg;
    size_t stat = 0;
  };
  /// A depth camera (libgazebo_ros_openni_kinect): rgb, depth, cloud at the sensor rate; both
  /// camera_infos at the plugin's updateRate.
  struct DepthIo {
    size_t robot = 0;
    std::unique_ptr<DepthCameraSensor> sensor;
    ros::Publisher image, depth, cloud, image_info, depth_info;
    Schedule schedule, info_schedule;
    BorrowedImage image_msg, depth_msg;  // borrowed from the sensor, as CameraIo's
    BorrowedPointCloud2 cloud_msg;
    sensor_msgs::CameraInfo info_msg;
    size_t stat = 0;
  };
  /// Published messages per sensor since the last status report, against the target rate.
  struct SensorStat {
    std::string name;  // e.g. "/scan"
    double target = 0.0;
    std::uint64_t count = 0;
    std::uint64_t skipped = 0;  // due while nobody subscribed (nothing rendered)
    std::uint64_t renders = 0;  // frames rendered / scans cast in total
  };

  /// The camera frames due at one step: rendered and published on camera_worker_'s thread
  /// from render_scene_, a snapshot of scene_ at that step.
  struct CameraJob {
    ros::Time stamp;
    struct Camera {
      size_t index;  // into cameras_ or depth_cameras_
      Eigen::Isometry3d X_WL;
      DepthOutputs want;  // depth cameras only
    };
    std::vector<Camera> cameras, depths;
  };

  /// Loads one robot from the parameters in `rp`; `name` fixes its name (else ~robot_name).
  void loadRobot(const ros::NodeHandle& rp, const std::string& name);
  /// Advertises `topic` for a robot's sensor; throws when another sensor publishes there.
  void claimTopic(const std::string& topic, const std::string& owner);
  bool ensureRenderer();
  void setUpCamera(size_t robot_index, const std::string& link, const SensorSpec& spec);
  void publishCameras(double t, const ros::Time& stamp);
  void renderCameras(CameraJob& job);  // on the frame worker's thread
  void publishStatus();
  void setUpSensors(size_t robot_index, const ros::NodeHandle& rp);
  /// Brings the scene's robot bodies to the current physics poses, once per step.
  void updateScene();
  void setUpJointStates(RobotIo& io);
  void stepOnce();
  void publishDue();
  void publishClock();
  void restartSchedules();

  bool onPause(std_srvs::Empty::Request&, std_srvs::Empty::Response&);
  bool onUnpause(std_srvs::Empty::Request&, std_srvs::Empty::Response&);
  bool onResetSimulation(std_srvs::Empty::Request&, std_srvs::Empty::Response&);
  bool onResetWorld(std_srvs::Empty::Request&, std_srvs::Empty::Response&);
  bool onSetModelState(SetModelState::Request& req, SetModelState::Response& res);
  bool onGetModelState(GetModelState::Request& req, GetModelState::Response& res);

  ros::NodeHandle nh_, pnh_;
  ros::CallbackQueue queue_;  // commands and services run between steps, in this thread
  std::unique_ptr<WorldDescription> world_;
  std::unique_ptr<Simulation> sim_;
  Scene scene_;  // what sensors see: the world's models and every robot's links
  std::uint64_t scene_step_ = ~0ull;  // step count the scene's poses belong to
  RayCaster caster_;
  std::vector<LidarIo> lidars_;
  std::unique_ptr<Renderer> renderer_;
  bool renderer_failed_ = false;
  std::vector<CameraIo> cameras_;
  std::vector<DepthIo> depth_cameras_;
  tf2_ros::StaticTransformBroadcaster static_tf_;
  std::vector<SensorStat> stats_;  // lidars, then cameras, then depth cameras (image topics)
  ros::Publisher diagnostics_pub_;
  double status_period_ = 5.0;  // wall seconds between status reports
  ros::WallTime status_wall_;
  double status_sim_ = 0.0;
  std::uint64_t seed_ = 0;
  std::vector<RobotIo> robots_;
  std::unique_ptr<ContactPublisher> contacts_;  // robots' contacts and their counts
  std::map<std::string, std::string> topic_owner_;  // sensor topics: who publishes there

  ros::Publisher clock_pub_;
  Schedule clock_schedule_;
  double ground_truth_rate_ = 50.0;
  double real_time_factor_ = 1.0;
  bool paused_ = false;
  bool pacing_reset_ = true;
  std::vector<ros::ServiceServer> services_;

  CameraJob due_frames_;  // filled each step, handed to the worker (capacity kept)
  Scene render_scene_;    // the worker's snapshot of scene_
  // Started with the first frame; reset first in ~SimNode (it uses the sensors above).
  std::unique_ptr<FrameWorker<CameraJob>> camera_worker_;
};

}  // namespace tianracer_sim

#endif  // TIANRACER_SIM_ROS_SIM_NODE_H
