// The gazebo_plugins model plugins that move a mobile robot from geometry_msgs/Twist and report
// its odometry, as gazebo_plugins (noetic-devel) does them. ROS-free: the parameters, the drive
// maths and the odometry; the simulator reads the joints and the model's motion and applies the
// commands (sim_drive.h), the node subscribes and publishes (ros/plugins/).
//
//  - libgazebo_ros_diff_drive (gazebo_plugins/src/gazebo_ros_diff_drive.cpp): two wheel
//    joints driven by velocity motors capped at <wheelTorque>, rim speeds
//    v -+ w * wheelSeparation / 2, an optional <wheelAcceleration> ramp, odometry from the
//    world (the model's pose) or the wheel encoders;
//  - libgazebo_ros_skid_steer_drive (gazebo_ros_skid_steer_drive.cpp): the same on four
//    joints (front and rear of a side at the same speed), capped at <torque>, odometry from
//    the world;
//  - libgazebo_ros_planar_move (gazebo_ros_planar_move.cpp): sets the model's velocity in the
//    plane every step (x, y of the twist in the robot's heading, yaw rate), odometry from the
//    pose differences between publications.
// Each update happens when `t - last > period` as upstream's, the diff and skid drives
// keeping a grid (last += period), planar_move restarting from the publication (last = t).
#ifndef TIANRACER_SIM_PLUGINS_DRIVES_DRIVES_H
#define TIANRACER_SIM_PLUGINS_DRIVES_DRIVES_H

#include <array>
#include <string>
#include <vector>

#include <Eigen/Geometry>

#include "tianracer_sim/model/robot_model.h"
#include "tianracer_sim/plugins/sensor_topics.h"
#include "tianracer_sim/plugins/link_data.h"

namespace tianracer_sim {

enum class DriveKind { kDiffDrive, kSkidSteer, kPlanarMove };
enum class OdomSource { kEncoder, kWorld };

struct DriveConfig {
  DriveKind kind = DriveKind::kDiffDrive;
  std::string name;      // the plugin's name
  std::string filename;  // e.g. libgazebo_ros_diff_drive.so
  /// The namespace of its node handle as the plugin makes it: diff drive <robotNamespace>, or
  /// the model's name when absent or empty; skid steer and planar_move <robotNamespace> or ""
  /// (the node's own, "/").
  std::string robot_namespace;
  std::string command_topic = "cmd_vel";
  std::string odometry_topic = "odom";
  std::string odometry_frame = "odom";
  std::string robot_base_frame = "base_footprint";
  OdomSource odometry_source = OdomSource::kWorld;  // diff drive's <odometrySource>
  /// Diff drive's <publishTf>: false advertises no odometry topic and publishes neither
  /// odometry nor its TF (upstream ties the odometry publisher to it).
  bool publish_odometry = true;
  /// The odom -> base TF: diff drive <publishOdomTF> (true), skid steer <broadcastTF> (false),
  /// planar_move always.
  bool publish_odom_tf = true;
  bool publish_wheel_tf = false;           // diff drive <publishWheelTF>
  bool publish_wheel_joint_state = false;  // diff drive <publishWheelJointState>
  double wheel_separation = 0.34;  // m (skid steer's default 0.4)
  double wheel_diameter = 0.15;    // m
  double wheel_torque = 5.0;       // N m, the motors' cap (skid steer's <torque>)
  double wheel_acceleration = 0.0; // m/s^2 of the rim; 0 = none
  /// Hz: diff/skid <updateRate> (100; <= 0: every step), planar_move <odometryRate> (20;
  /// <= 0: no odometry).
  double update_rate = 100.0;
  double cmd_timeout = -1.0;  // planar_move <cmdTimeout>, s; < 0: commands never expire
  /// The wheel joints: diff drive left, right; skid steer left front, right front, left rear,
  /// right rear. Empty for planar_move.
  std::vector<std::string> joints;
  std::array<double, 36> pose_covariance{};
  std::array<double, 36> twist_covariance{};
  std::string ros_debug_level = "na";  // <rosDebugLevel> (GazeboRos' plugins: diff drive)
  /// What upstream warns about at load: each parameter left out and its default
  /// ("missing <updateRate>, defaults to 100"), in the order it reads them.
  std::vector<std::string> defaulted;

  std::string commandTopic() const { return resolveTopic(robot_namespace, command_topic); }
  std::string odometryTopic() const { return resolveTopic(robot_namespace, odometry_topic); }
  std::string jointStatesTopic() const { return resolveTopic(robot_namespace, "joint_states"); }
  bool drivesJoints() const { return kind != DriveKind::kPlanarMove; }
};

/// Reads the plugin (a SensorSpec of type "", modelPluginSensor()) as gazebo_plugins does,
/// with its defaults. Stricter than upstream where upstream would load nonsense: a value that
/// is not a number, not finite, a wheelDiameter or wheelSeparation <= 0, a negative torque,
/// acceleration or rate, a boolean that is not true/false/1/0 or an unknown odometrySource
/// throw SensorError naming the plugin, model, element and value. Parameters the plugin does
/// not read go to `warn`. Joints are checked by the simulator (it knows the model's).
DriveConfig parseDriveConfig(const SensorSpec& plugin, const std::string& model_name,
                             const WarningSink& warn = {});
/// The odometry (nav_msgs/Odometry at update_rate), joint_states when asked, and the command
/// topic (geometry_msgs/Twist, subscribed: rate 0).
std::vector<SensorTopic> publishedTopics(const DriveConfig& config);

/// Rim speeds (m/s) of the left and right wheels for a twist: v -+ w s / 2
/// (getWheelVelocities of the diff and skid steer drives).
struct WheelSpeeds {
  double left = 0.0, right = 0.0;
};
WheelSpeeds wheelSpeeds(double v, double w, double separation);

/// gazebo_ros_diff_drive's acceleration limit, one update of `dt` s: with accel 0, or either
/// wheel within 0.01 m/s of its target, the target itself; otherwise each side's issued speed
/// moves by the difference between target and current speed, at most accel * dt:
///   issued += clamp(target - current, -accel dt, accel dt)
/// and the issued speeds are commanded. `issued` persists between updates (upstream's
/// wheel_speed_instr_, 0 at start).
WheelSpeeds rampWheelSpeeds(const WheelSpeeds& target, const WheelSpeeds& current, double accel,
                            double dt, WheelSpeeds* issued);

/// nav_msgs/Odometry as the plugins fill it (frames are the node's).
struct DriveOdometry {
  Eigen::Vector3d position = Eigen::Vector3d::Zero();
  Eigen::Quaterniond orientation = Eigen::Quaterniond::Identity();
  Eigen::Vector3d linear = Eigen::Vector3d::Zero();   // in the base frame
  Eigen::Vector3d angular = Eigen::Vector3d::Zero();
  std::array<double, 36> pose_covariance{};
  std::array<double, 36> twist_covariance{};
  /// The odom -> base TF: the encoders' pose, else the model's whole pose (the skid steer's and
  /// planar_move's messages leave z at 0, their TF does not).
  Eigen::Isometry3d X_OB = Eigen::Isometry3d::Identity();
};

/// gazebo_ros_diff_drive's encoder odometry (UpdateOdometryEncoder, Siegwart 2011 p. 337),
/// integrated at every step from the wheel joints' rates (rad/s):
///   sl = wl r dt, sr = wr r dt, dtheta = (sr - sl) / b,
///   dx = (sl + sr)/2 cos(theta + dtheta/2), dy = (sl + sr)/2 sin(theta + dtheta/2),
/// twist v = (sl + sr) / (2 dt) (upstream: its magnitude, sqrt(dx^2 + dy^2) / dt, which is
/// positive backwards too), w = dtheta / dt.
class EncoderOdometry {
 public:
  void reset() { *this = EncoderOdometry(); }
  void update(double omega_left, double omega_right, double radius, double separation, double dt);
  double x() const { return x_; }
  double y() const { return y_; }
  double theta() const { return theta_; }
  double v() const { return v_; }
  double w() const { return w_; }

 private:
  double x_ = 0.0, y_ = 0.0, theta_ = 0.0, v_ = 0.0, w_ = 0.0;
};

/// Yaw of a rotation as ignition::math::Quaternion::Yaw() gives it.
double yawOf(const Eigen::Quaterniond& q);

/// The odometry of the diff drive (world source) and the skid steer: the model frame's pose in
/// the world, the twist turned into the heading frame: x = cos(yaw) vx + sin(yaw) vy,
/// y = cos(yaw) vy - sin(yaw) vx, angular z = the world yaw rate. `with_z`: the diff drive fills
/// position z, the skid steer leaves it 0.
void worldOdometry(const LinkState& model, bool with_z, DriveOdometry* odom);

/// One drive plugin's state between steps, without the physics: the caller reads the wheel
/// joints' rates and the model's motion, calls update() after every physics step (time t, as
/// upstream's WorldUpdateBegin sees it before the next one), and applies what it says.
class DriveCore {
 public:
  explicit DriveCore(DriveConfig config);
  const DriveConfig& config() const { return config_; }

  /// A cmd_vel (linear x, y and angular z) received at sim time t. Non-finite values are
  /// refused (false), the previous command stays.
  bool setCommand(double vx, double vy, double wz, double t);
  /// Time went back or the start: schedules and odometry restart at t from the model's pose.
  void restart(double t, const LinkState& model);

  struct Step {
    bool due = false;              // odometry (and wheel TF, joint states) go out now
    bool set_wheels = false;       // command the wheel joints (diff, skid) ...
    std::vector<double> wheel_omega;  // ... to these rates (rad/s), joints' order, torque-capped
    bool set_twist = false;        // planar_move: the model's velocity, world frame
    Eigen::Vector3d linear_W = Eigen::Vector3d::Zero();
    Eigen::Vector3d angular_W = Eigen::Vector3d::Zero();
  };
  /// After the physics step that ended at t: `model` is the model frame's state, `omega` the
  /// wheel joints' rates (config().joints order; empty for planar_move).
  const Step& update(double t, const LinkState& model, const std::vector<double>& omega);
  /// The odometry as of the last due update.
  const DriveOdometry& odometry() const { return odom_; }

 private:
  DriveConfig config_;
  double vx_ = 0.0, vy_ = 0.0, wz_ = 0.0;
  double last_cmd_ = 0.0;      // planar_move: when the last command came
  double last_update_ = 0.0;   // the update schedule
  double last_odom_ = 0.0;     // encoder integration
  bool started_ = false;
  LinkState last_pose_;        // planar_move: the model at the last publication
  WheelSpeeds issued_;
  EncoderOdometry encoder_;
  DriveOdometry odom_;
  Step step_;
};

}  // namespace tianracer_sim

#endif  // TIANRACER_SIM_PLUGINS_DRIVES_DRIVES_H
