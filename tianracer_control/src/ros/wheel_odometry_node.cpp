// wheel_odometry_node: /<ns>/joint_states -> nav_msgs/Odometry on /<ns>/odom and TF
// odom -> base_link, through the bicycle model (odometry.h). Wiring only.
#include <cmath>
#include <string>
#include <vector>

#include <nav_msgs/Odometry.h>
#include <ros/ros.h>
#include <sensor_msgs/JointState.h>
#include <tf2_ros/transform_broadcaster.h>

#include "tianracer_control/odometry.h"
#include "tianracer_control/naming.h"
#include "tianracer_control/ros/geometry_params.h"
#include "tianracer_control/ros/msg_conversion.h"
#include "tianracer_control/ros/node_main.h"

namespace tianracer_control {

namespace {

CovarianceDiagonal covarianceParam(const ros::NodeHandle& pnh, const std::string& key,
                                   const CovarianceDiagonal& fallback) {
  XmlRpc::XmlRpcValue v;
  if (!pnh.getParam(key, v)) return fallback;
  const std::string bad = "parameter " + pnh.resolveName(key) +
                          " must list 6 numbers (x y z roll pitch yaw variances)";
  if (v.getType() != XmlRpc::XmlRpcValue::TypeArray || v.size() != 6) throw AckermannError(bad);
  CovarianceDiagonal out;
  for (int i = 0; i < 6; ++i) {
    if (v[i].getType() == XmlRpc::XmlRpcValue::TypeDouble) {
      out[i] = static_cast<double>(v[i]);
    } else if (v[i].getType() == XmlRpc::XmlRpcValue::TypeInt) {
      out[i] = static_cast<int>(v[i]);
    } else {
      throw AckermannError(bad);
    }
  }
  return out;
}

}  // namespace

class WheelOdometryNode {
 public:
  WheelOdometryNode(ros::NodeHandle nh, ros::NodeHandle pnh) {
    const AckermannSetup setup = loadAckermannSetup(nh, pnh);
    joints_ = setup.joints;
    odometry_.setGeometry(setup.geometry);
    odometry_.reset();

    std::string ns = pnh.param<std::string>("robot_namespace", "/tianracer");
    if (!ns.empty() && ns.back() == '/') ns.pop_back();
    const std::string in = pnh.param<std::string>("joint_states_topic", ns + "/joint_states");
    const std::string out = pnh.param<std::string>("odom_topic", ns + "/odom");
    // The child frame is the model's base link as the model names it (car1/base_link for a
    // prefix:=car1 model); the odometry frame is the simulator's (its ~odom_frame).
    pnh.param<std::string>("odom_frame", odom_frame_, "odom");
    base_frame_ = setup.base_frame;
    // Several cars share one TF tree through a tf_prefix found from the robot's namespace, as
    // robot_state_publisher and the gazebo_ros plugins find it (two_cars.launch).
    std::string key, tf_prefix;
    if (ros::NodeHandle(ns.empty() ? "/" : ns).searchParam("tf_prefix", key)) {
      nh.getParam(key, tf_prefix);
    }
    odom_frame_ = resolveFrame(tf_prefix, odom_frame_);
    base_frame_ = resolveFrame(tf_prefix, base_frame_);
    pnh.param("publish_tf", publish_tf_, true);
    pnh.param("use_wheel_positions", use_positions_, true);
    // Planar motion: z, roll and pitch are not observed (large variance, as diff_drive_controller).
    pose_cov_ = covarianceParam(pnh, "pose_covariance_diagonal",
                                {0.001, 0.001, 1e6, 1e6, 1e6, 0.01});
    twist_cov_ = covarianceParam(pnh, "twist_covariance_diagonal",
                                 {0.001, 0.001, 1e6, 1e6, 1e6, 0.01});

    pub_ = nh.advertise<nav_msgs::Odometry>(out, 10);
    // A deep queue: a node starved of CPU while the sim runs faster than real time must not
    // drop samples (a gap is integrated with the hinge angles at its end).
    sub_ = nh.subscribe(in, 1000, &WheelOdometryNode::onJointStates, this);
    ROS_INFO_STREAM("odometry from " << sub_.getTopic() << " (wheel "
                                     << (use_positions_ ? "positions" : "velocities") << ") to "
                                     << pub_.getTopic() << ", TF " << odom_frame_ << " -> "
                                     << base_frame_ << (publish_tf_ ? "" : " (not published)"));
  }

 private:
  void onJointStates(const sensor_msgs::JointState::ConstPtr& msg) {
    AckermannJointSample s;
    std::string missing;
    if (!fromJointStateMsg(*msg, joints_, &s, &missing)) {
      ROS_WARN_THROTTLE(5.0, "%s: %s", sub_.getTopic().c_str(), missing.c_str());
      return;
    }
    const ros::Time now = ros::Time::now();
    const ros::Time stamp = msg->header.stamp.isZero() ? now : msg->header.stamp;
    // A message from before a sim reset, read after this node's clock went back: drop it
    // rather than jump back and forth between the two timelines. Only after the clock went
    // back: a node that merely lags (starved of CPU, /clock behind the messages) keeps every
    // message.
    if (!last_now_.isZero() && now < last_now_) clock_went_back_ = true;
    last_now_ = now;
    if (clock_went_back_) {
      if (stamp > now + ros::Duration(1.0)) return;
      clock_went_back_ = false;
    }

    if (has_last_ && stamp < last_stamp_) {
      ROS_WARN_STREAM("time jumped back from " << last_stamp_ << " to " << stamp
                                               << " (sim reset?): odometry reset to the origin");
      odometry_.reset();
      has_last_ = false;
    }
    if (!has_last_) {
      // First sample of a timeline: only the starting wheel positions.
      if (s.has_wheel_positions) {
        odometry_.updateFromPositions(s.left_rear_position, s.right_rear_position, s.left_hinge,
                                      s.right_hinge, 0.0);
      }
      has_last_ = true;
      last_stamp_ = stamp;
      publish(stamp);
      return;
    }
    const double dt = (stamp - last_stamp_).toSec();
    if (dt <= 0.0) return;  // same stamp again: nothing new, and no repeated TF
    if (use_positions_ && s.has_wheel_positions) {
      odometry_.updateFromPositions(s.left_rear_position, s.right_rear_position, s.left_hinge,
                                    s.right_hinge, dt);
    } else if (s.has_wheel_velocities) {
      odometry_.update(s.left_rear_velocity, s.right_rear_velocity, s.left_hinge, s.right_hinge,
                       dt);
    }
    last_stamp_ = stamp;
    publish(stamp);
  }

  void publish(const ros::Time& stamp) {
    pub_.publish(toOdometryMsg(odometry_, stamp, odom_frame_, base_frame_, pose_cov_, twist_cov_));
    if (publish_tf_) tf_.sendTransform(toTransformMsg(odometry_, stamp, odom_frame_, base_frame_));
  }

  AckermannJointNames joints_;
  BicycleOdometry odometry_;
  std::string odom_frame_, base_frame_;
  bool publish_tf_ = true;
  bool use_positions_ = true;
  CovarianceDiagonal pose_cov_{}, twist_cov_{};
  ros::Publisher pub_;
  ros::Subscriber sub_;
  tf2_ros::TransformBroadcaster tf_;
  bool has_last_ = false;
  ros::Time last_stamp_;
  ros::Time last_now_;
  bool clock_went_back_ = false;
};

}  // namespace tianracer_control

int main(int argc, char** argv) {
  return tianracer_control::runNode<tianracer_control::WheelOdometryNode>(argc, argv,
                                                                          "wheel_odometry_node");
}
