// cmd_vel_node: /cmd_vel (geometry_msgs/Twist) or ackermann_cmd (ackermann_msgs/
// AckermannDriveStamped or AckermannDrive) -> the steering hinge position controllers and rear
// wheel velocity controllers (std_msgs/Float64), through exact Ackermann geometry.
// The maths is in CmdVelProcessor / ackermann.h; this file wires parameters, topics and time.
// Every command message taken (applied or rejected) is echoed on ~received (std_msgs/Time: the
// sim time it was taken at): the simulator's lockstep waits for that echo, as a reply topic,
// before it publishes the step's /clock, so the node takes a driver's answer before the tick it
// answers, at a defined sim time, however its connections to the driver and to the simulator
// interleave (docs/simulator.md, lockstep).
#include <cmath>
#include <memory>
#include <string>

#include <ackermann_msgs/AckermannDrive.h>
#include <ackermann_msgs/AckermannDriveStamped.h>
#include <geometry_msgs/Twist.h>
#include <ros/ros.h>
#include <std_msgs/Float64.h>
#include <std_msgs/Time.h>
#include <topic_tools/shape_shifter.h>

#include "tianracer_control/cmd_vel.h"
#include "tianracer_control/ros/geometry_params.h"
#include "tianracer_control/ros/msg_conversion.h"
#include "tianracer_control/ros/node_main.h"

namespace tianracer_control {

namespace {

double numberParam(const ros::NodeHandle& pnh, const std::string& key, double fallback) {
  double v = fallback;
  getNumberParam(pnh, key, &v);
  return v;
}

// The command topic (under `ns`) of the controller of `joint` in the ros_control YAML loaded
// under `control_ns` (a user's controllers carry their own names), else of the controller
// named `fallback`.
std::string commandTopic(const std::string& ns, const std::string& control_ns,
                         const std::string& joint, const std::string& fallback) {
  XmlRpc::XmlRpcValue controllers;
  if (ros::NodeHandle().getParam(control_ns.empty() ? "/" : control_ns, controllers) &&
      controllers.getType() == XmlRpc::XmlRpcValue::TypeStruct) {
    for (auto& kv : controllers) {
      XmlRpc::XmlRpcValue& c = kv.second;
      if (c.getType() == XmlRpc::XmlRpcValue::TypeStruct && c.hasMember("joint") &&
          c["joint"].getType() == XmlRpc::XmlRpcValue::TypeString &&
          static_cast<std::string>(c["joint"]) == joint) {
        return ns + "/" + kv.first + "/command";
      }
    }
  }
  return ns + "/" + fallback + "/command";
}

}  // namespace

class CmdVelNode {
 public:
  CmdVelNode(ros::NodeHandle nh, ros::NodeHandle pnh) {
    const AckermannSetup setup = loadAckermannSetup(nh, pnh);
    const AckermannJointNames& joints = setup.joints;
    geometry_ = setup.geometry;

    AckermannOptions options;
    pnh.param("angular_z_is_steering_angle", options.angular_z_is_steering_angle, false);
    pnh.param("differential", options.differential, false);
    CmdVelLimits limits;
    limits.max_speed = numberParam(pnh, "max_speed", limits.max_speed);
    limits.max_accel = numberParam(pnh, "max_accel", limits.max_accel);
    limits.cmd_timeout = numberParam(pnh, "cmd_timeout", limits.cmd_timeout);
    const double rate = numberParam(pnh, "publish_rate", 50.0);
    if (!(rate > 0.0) || !std::isfinite(rate)) {
      throw AckermannError("parameter ~publish_rate must be > 0, got " + std::to_string(rate));
    }
    if (limits.max_speed < 0.0 || limits.max_accel < 0.0 || limits.cmd_timeout < 0.0) {
      throw AckermannError("parameters ~max_speed, ~max_accel and ~cmd_timeout must be >= 0");
    }
    processor_ = std::make_unique<CmdVelProcessor>(geometry_, options, limits);

    std::string ns = pnh.param<std::string>("robot_namespace", "/tianracer");
    if (!ns.empty() && ns.back() == '/') ns.pop_back();
    std::string control_ns = pnh.param<std::string>("control_namespace", ns);
    if (!control_ns.empty() && control_ns.back() == '/') control_ns.pop_back();
    const std::string cmd_vel_topic = pnh.param<std::string>("cmd_vel_topic", "cmd_vel");
    const std::string ackermann_topic =
        pnh.param<std::string>("ackermann_topic", "ackermann_cmd");
    // Each wheel's command topic: ~<param>, else the one its controller gets (commandTopic).
    auto command_topic = [&](const char* param, const std::string& joint, const char* fallback) {
      return pnh.param<std::string>(param, commandTopic(ns, control_ns, joint, fallback));
    };
    const std::string left_steer = command_topic("left_steering_topic", joints.left_hinge,
                                                 "left_steering_hinge_position_controller");
    const std::string right_steer = command_topic("right_steering_topic", joints.right_hinge,
                                                  "right_steering_hinge_position_controller");
    const std::string left_wheel = command_topic("left_rear_wheel_topic", joints.left_rear_wheel,
                                                 "left_rear_wheel_velocity_controller");
    const std::string right_wheel = command_topic(
        "right_rear_wheel_topic", joints.right_rear_wheel, "right_rear_wheel_velocity_controller");

    ROS_INFO_STREAM("angular.z is the "
                    << (options.angular_z_is_steering_angle ? "steering angle (rad)"
                                                            : "yaw rate (rad/s, REP-103)")
                    << "; rear wheels " << (options.differential ? "differential" : "equal speed")
                    << "; max_speed " << limits.max_speed << " m/s, max_accel "
                    << limits.max_accel << (limits.max_accel > 0.0 ? " m/s^2" : " (none)")
                    << ", cmd_timeout " << limits.cmd_timeout << " s, publish_rate " << rate
                    << " Hz");

    left_steer_pub_ = nh.advertise<std_msgs::Float64>(left_steer, 1);
    right_steer_pub_ = nh.advertise<std_msgs::Float64>(right_steer, 1);
    left_wheel_pub_ = nh.advertise<std_msgs::Float64>(left_wheel, 1);
    right_wheel_pub_ = nh.advertise<std_msgs::Float64>(right_wheel, 1);
    ROS_INFO_STREAM("publishing " << left_steer_pub_.getTopic() << ", "
                                  << right_steer_pub_.getTopic() << ", "
                                  << left_wheel_pub_.getTopic() << ", "
                                  << right_wheel_pub_.getTopic());
    received_pub_ = pnh.advertise<std_msgs::Time>("received", 10);
    sub_ = nh.subscribe(cmd_vel_topic, 10, &CmdVelNode::onTwist, this);
    // Either Ackermann type on one topic, whichever its publishers use (F1TENTH stacks send
    // the stamped one, simpler drivers the bare AckermannDrive).
    if (!ackermann_topic.empty()) {
      nh_ = nh;
      ackermann_topic_ = ackermann_topic;
      ackermann_sub_ = nh.subscribe(ackermann_topic, 10, &CmdVelNode::onAckermann, this);
    }
    ROS_INFO_STREAM("listening on " << sub_.getTopic() << " (geometry_msgs/Twist)"
                    << (ackermann_topic.empty() ? std::string()
                                                : " and " + ackermann_sub_.getTopic() +
                                                      " (ackermann_msgs/AckermannDriveStamped "
                                                      "or AckermannDrive)"));
    timer_ = nh.createTimer(ros::Duration(1.0 / rate), &CmdVelNode::onTimer, this);
  }

 private:
  void onTwist(const geometry_msgs::Twist::ConstPtr& msg) {
    takeTwist(*msg);
    echo();
  }

  void onAckermann(const topic_tools::ShapeShifter::ConstPtr& msg) {
    takeAckermann(msg);
    echo();
  }

  void echo() {
    std_msgs::Time m;
    m.data = ros::Time::now();
    received_pub_.publish(m);
  }

  void takeTwist(const geometry_msgs::Twist& msg) {
    double v = 0.0, w = 0.0;
    const double t = ros::Time::now().toSec();
    if (!fromTwistMsg(msg, &v, &w)) {
      ROS_WARN_THROTTLE(1.0, "ignoring %s with a non-finite value (linear.x %g, angular.z %g)",
                        sub_.getTopic().c_str(), msg.linear.x, msg.angular.z);
      return;
    }
    if (processor_->setTwist(v, w, t) == CmdVelProcessor::Input::kSpeedClamped) {
      ROS_WARN_THROTTLE(5.0, "linear.x %g clamped to max_speed", v);
    }
    reportTwoSources(t);
  }

  void takeAckermann(const topic_tools::ShapeShifter::ConstPtr& msg) {
    ackermann_msgs::AckermannDrive drive;
    const std::string& type = msg->getDataType();
    if (type == ros::message_traits::DataType<ackermann_msgs::AckermannDriveStamped>::value() &&
        msg->getMD5Sum() == ros::message_traits::MD5Sum<ackermann_msgs::AckermannDriveStamped>::value()) {
      drive = msg->instantiate<ackermann_msgs::AckermannDriveStamped>()->drive;
    } else if (type == ros::message_traits::DataType<ackermann_msgs::AckermannDrive>::value() &&
               msg->getMD5Sum() == ros::message_traits::MD5Sum<ackermann_msgs::AckermannDrive>::value()) {
      drive = *msg->instantiate<ackermann_msgs::AckermannDrive>();
    } else {
      ROS_WARN_THROTTLE(5.0, "ignoring %s of type %s (md5sum %s): expected "
                        "ackermann_msgs/AckermannDriveStamped or AckermannDrive",
                        ackermann_sub_.getTopic().c_str(), type.c_str(), msg->getMD5Sum().c_str());
      return;
    }
    const double t = ros::Time::now().toSec();
    const AckermannDriveResult r = processor_->setAckermann(fromAckermannDriveMsg(drive), t);
    if (r.rejected) {
      ROS_WARN_THROTTLE(1.0, "ignoring %s with a non-finite value (speed %g, steering_angle %g, "
                        "steering_angle_velocity %g, acceleration %g)",
                        ackermann_sub_.getTopic().c_str(), drive.speed, drive.steering_angle,
                        drive.steering_angle_velocity, drive.acceleration);
      return;
    }
    if (r.speed_clamped) {
      ROS_WARN_THROTTLE(5.0, "%s: speed %g clamped to max_speed",
                        ackermann_sub_.getTopic().c_str(), drive.speed);
    }
    if (r.steering_clamped) {
      ROS_WARN_THROTTLE(5.0, "%s: steering_angle %g clamped to the joint limits",
                        ackermann_sub_.getTopic().c_str(), drive.steering_angle);
    }
    reportTwoSources(t);
  }

  void reportTwoSources(double t) {
    if (two_sources_reported_ || !processor_->twoSourcesActive(t)) return;
    ROS_WARN("both %s and %s are commanding the car: the latest message wins (reported once)",
             sub_.getTopic().c_str(), ackermann_sub_.getTopic().c_str());
    two_sources_reported_ = true;
  }

  void onTimer(const ros::TimerEvent&) {
    // A type-agnostic subscriber takes the md5sum of its first publisher for good; once every
    // publisher has left, subscribe afresh so that the next one may use the other type.
    if (ackermann_sub_) {
      if (ackermann_sub_.getNumPublishers() > 0) {
        ackermann_connected_ = true;
      } else if (ackermann_connected_) {
        ackermann_sub_.shutdown();  // first: a live subscription would be reused as it is
        ackermann_sub_ = nh_.subscribe(ackermann_topic_, 10, &CmdVelNode::onAckermann, this);
        ackermann_connected_ = false;
      }
    }
    const bool was_timed_out = processor_->timedOut();
    const AckermannCommand c = processor_->update(ros::Time::now().toSec());
    if (c.clamped && !clamp_reported_) {
      ROS_WARN("steering request beyond the joint limits: clamped to the bicycle angle %.4f rad "
               "(turning radius %.3f m); reported once",
               c.delta, geometry_.wheelbase / std::tan(std::abs(c.delta)));
      clamp_reported_ = true;
    }
    if (processor_->timedOut() && !was_timed_out) {
      ROS_INFO("no command on %s%s%s for the command timeout: stopping (steering held)",
               sub_.getTopic().c_str(), ackermann_sub_ ? " or " : "",
               ackermann_sub_ ? ackermann_sub_.getTopic().c_str() : "");
    }
    left_steer_pub_.publish(toFloat64Msg(c.left_steer));
    right_steer_pub_.publish(toFloat64Msg(c.right_steer));
    left_wheel_pub_.publish(toFloat64Msg(c.left_wheel_omega));
    right_wheel_pub_.publish(toFloat64Msg(c.right_wheel_omega));
  }

  AckermannGeometry geometry_;
  std::unique_ptr<CmdVelProcessor> processor_;
  ros::Publisher left_steer_pub_, right_steer_pub_, left_wheel_pub_, right_wheel_pub_;
  ros::Publisher received_pub_;
  ros::NodeHandle nh_;
  std::string ackermann_topic_;
  ros::Subscriber sub_, ackermann_sub_;
  bool ackermann_connected_ = false;
  ros::Timer timer_;
  bool clamp_reported_ = false;
  bool two_sources_reported_ = false;
};

}  // namespace tianracer_control

int main(int argc, char** argv) {
  return tianracer_control::runNode<tianracer_control::CmdVelNode>(argc, argv, "cmd_vel_node");
}
