// libgazebo_ros_diff_drive, libgazebo_ros_skid_steer_drive, libgazebo_ros_planar_move: the
// cmd_vel subscriber, the odometry, its TF, the wheels' TF and joint states (plugins/drives/drives.h).
#include <cmath>
#include <memory>

#include <geometry_msgs/Twist.h>
#include <nav_msgs/Odometry.h>
#include <ros/console.h>
#include <sensor_msgs/JointState.h>
#include <tf2_ros/transform_broadcaster.h>

#include "factories.h"
#include "tianracer_sim/common/text.h"
#include "tianracer_sim/ros/state_msgs.h"

namespace tianracer_sim {
namespace {

// GazeboRos::readCommonParameter: <rosDebugLevel> sets the level of the process's default
// logger (upstream: all of gzserver; here: the sim node). "na" (the default) changes nothing.
void applyDebugLevel(const std::string& level_name, const std::string& who) {
  const std::string l = lowerCase(level_name);
  ros::console::levels::Level level;
  if (l == "debug") level = ros::console::levels::Debug;
  else if (l == "info") level = ros::console::levels::Info;
  else if (l == "warn") level = ros::console::levels::Warn;
  else if (l == "error") level = ros::console::levels::Error;
  else if (l == "fatal") level = ros::console::levels::Fatal;
  else return;
  if (ros::console::set_logger_level(ROSCONSOLE_DEFAULT_NAME, level))
    ros::console::notifyLoggerLevelsChanged();
  ROS_INFO("%s: <rosDebugLevel> = %s", who.c_str(), level_name.c_str());
}

class DrivePublisher : public SensorListener {
 public:
  DrivePublisher(SimDrive& drive, const PublisherSetup& setup) : drive_(drive) {
    const DriveConfig& c = drive.config();
    who_ = setup.owner() + " " + c.filename + " '" + c.name + "'";
    // What upstream warns about at load, once.
    for (const std::string& d : c.defaulted)
      ROS_WARN("%s (ns = %s): %s", who_.c_str(), c.robot_namespace.c_str(), d.c_str());
    applyDebugLevel(c.ros_debug_level, who_);
    ros::NodeHandle root = setup.root;
    const bool odometry = (drive.config().kind == DriveKind::kPlanarMove) ? c.update_rate > 0.0
                                                                          : c.publish_odometry;
    if (odometry) {
      setup.claim_topic(c.odometryTopic(), who_);
      odom_pub_ = root.advertise<nav_msgs::Odometry>(c.odometryTopic(), 1);
    }
    if (c.publish_wheel_joint_state)
      joint_pub_ = root.advertise<sensor_msgs::JointState>(c.jointStatesTopic(), 1000);
    command_topic_ = c.commandTopic();
    cmd_sub_ = root.subscribe<geometry_msgs::Twist>(
        command_topic_, 1, [this](const geometry_msgs::Twist::ConstPtr& m) { onCommand(*m); });
    tf_ = std::make_unique<tf2_ros::TransformBroadcaster>();
    drive.stat().name = c.odometryTopic();
    ROS_INFO("%s: %s -> %s, odometry %s (%s -> %s%s) at %g Hz", who_.c_str(),
             command_topic_.c_str(),
             c.kind == DriveKind::kPlanarMove ? "the model's velocity" : "wheel joints",
             odometry ? c.odometryTopic().c_str() : "off", drive.odomFrame().c_str(),
             drive.baseFrame().c_str(), c.publish_odom_tf ? ", TF" : "", c.update_rate);
  }

  SensorOutputs wanted(const SimSensor&, SensorOutputs due) override {
    // TF goes out whether or not anyone listens (as upstream); the topics only when heard.
    const DriveConfig& c = drive_.config();
    SensorOutputs want = due & SimDrive::kWheelTf;
    if ((due & SimDrive::kOdometry) && (c.publish_odom_tf || odom_pub_.getNumSubscribers() > 0))
      want |= SimDrive::kOdometry;
    if ((due & SimDrive::kJointState) && joint_pub_.getNumSubscribers() > 0)
      want |= SimDrive::kJointState;
    return want;
  }

  void onOutputs(const SimSensor&, SensorOutputs outputs, double t) override {
    const DriveConfig& c = drive_.config();
    const ros::Time stamp(t);
    if (outputs & SimDrive::kOdometry) {
      const DriveOdometry& o = drive_.odometry();
      if (c.publish_odom_tf)
        tf_->sendTransform(toTransform(o.X_OB, stamp, drive_.odomFrame(), drive_.baseFrame()));
      if (odom_pub_.getNumSubscribers() > 0) {
        toOdometry(o, stamp, drive_.odomFrame(), drive_.baseFrame(), &odom_);
        odom_pub_.publish(odom_);
      }
    }
    if (outputs & SimDrive::kWheelTf) {
      for (const SimDrive::WheelTf& w : drive_.wheelTransforms())
        tf_->sendTransform(toTransform(w.X_PC, stamp, w.parent_frame, w.child_frame));
    }
    if (outputs & SimDrive::kJointState) {
      // Upstream fills names and positions only.
      joints_.header.stamp = stamp;
      joints_.name = drive_.jointNames();
      joints_.position = drive_.jointPositions();
      joint_pub_.publish(joints_);
    }
  }

 private:
  void onCommand(const geometry_msgs::Twist& m) {
    if (!drive_.setCommand(m.linear.x, m.linear.y, m.angular.z)) {
      ROS_WARN_THROTTLE(1.0, "%s: %s: non-finite command (linear.x %g, linear.y %g, angular.z %g) "
                        "ignored; the previous one stays", who_.c_str(), command_topic_.c_str(),
                        m.linear.x, m.linear.y, m.angular.z);
    }
  }

  SimDrive& drive_;
  std::string who_, command_topic_;
  ros::Publisher odom_pub_, joint_pub_;
  ros::Subscriber cmd_sub_;
  std::unique_ptr<tf2_ros::TransformBroadcaster> tf_;
  nav_msgs::Odometry odom_;
  sensor_msgs::JointState joints_;
};

}  // namespace

std::unique_ptr<SensorListener> makeDrivePublisher(SimSensor& sensor, const PublisherSetup& setup) {
  return std::make_unique<DrivePublisher>(static_cast<SimDrive&>(sensor), setup);
}

TIANRACER_SENSOR_PUBLISHER(driveKind, makeDrivePublisher);

}  // namespace tianracer_sim
