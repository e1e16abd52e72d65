#include "tianracer_sim/ros/robot_bridge.h"

#include <algorithm>

#include <geometry_msgs/TransformStamped.h>
#include <nav_msgs/Odometry.h>

#include <tianracer_control/frames.h>

#include "tianracer_sim/model/sensor_topics.h"
#include "tianracer_sim/ros/state_msgs.h"

namespace tianracer_sim {

namespace tc = tianracer_control;

RobotBridge::RobotBridge(Simulator& sim, ModelId id, Options options, ros::NodeHandle root,
                         tf2_ros::StaticTransformBroadcaster& static_tf)
    : sim_(sim), id_(id), options_(std::move(options)) {
  SimRobot& robot = *sim_.robot(id_);
  physics_id_ = robot.id;
  const PhysicsRobot& pr = sim_.simulation().physics().robot(robot.id);
  base_frame_ = tc::resolveFrame(options_.tf_prefix, pr.tree().bodies.front().link);

  // world -> odom at the spawn pose: wheel odometry starts there, so rviz can show the
  // ground truth (world) and the odometry (odom) together.
  if (!options_.odom_frame.empty()) {
    geometry_msgs::TransformStamped tf;
    tf.header.frame_id = "world";
    tf.child_frame_id = tc::resolveFrame(options_.tf_prefix, options_.odom_frame);
    const geometry_msgs::Pose p = toPose(pr.spawnPose());
    tf.transform.translation.x = p.position.x;
    tf.transform.translation.y = p.position.y;
    tf.transform.translation.z = p.position.z;
    tf.transform.rotation = p.orientation;
    static_tf.sendTransform(tf);
  }

  setUpJointStates(root);
  ros::NodeHandle robot_nh(root, options_.ns);
  commands_ = std::make_shared<tc::ControllerCommandSubscribers>(robot_nh, robot.controllers);
  ground_truth_ = robot_nh.advertise<nav_msgs::Odometry>("ground_truth/odom", 10);
  ground_truth_schedule_.period =
      options_.ground_truth_rate > 0.0 ? 1.0 / options_.ground_truth_rate : 0.0;
}

void RobotBridge::setUpJointStates(ros::NodeHandle& root) {
  // Both the joint_state_publisher plugin and joint_state_controller publish JointState; when
  // they resolve to the same topic they become ONE stream (one publisher): the plugin's joints
  // in its order, then the controller's other joints, at the higher of the two rates.
  struct Request {
    std::string topic;
    std::vector<std::string> joints;
    double rate;
    std::string source;
  };
  std::vector<Request> requests;
  const SimRobot& robot = *sim_.robot(id_);
  const RobotModel& model = robot.model;
  const PhysicsRobot& pr = sim_.simulation().physics().robot(robot.id);
  if (const auto& jsp = model.ext.joint_state_publisher) {
    requests.push_back({resolveTopic(jsp->robot_namespace, "joint_states"), jsp->joint_names,
                        jsp->update_rate, "joint_state_publisher plugin"});
  }
  for (const auto& c : robot.controllers.controllers()) {
    if (auto* jsc = dynamic_cast<const tc::JointStateController*>(c.get())) {
      std::vector<std::string> joints;
      for (const auto& h : robot.handles) joints.push_back(h.name);
      requests.push_back({resolveTopic(options_.ns, "joint_states"), joints, jsc->publishRate(),
                          "joint_state_controller '" + c->name() + "'"});
    }
  }
  for (const Request& r : requests) {
    auto it = std::find_if(joint_states_.begin(), joint_states_.end(),
                           [&](const JointStateStream& s) { return s.pub.getTopic() == r.topic; });
    if (it == joint_states_.end()) {
      JointStateStream s;
      s.pub = root.advertise<sensor_msgs::JointState>(r.topic, 10);
      s.schedule.period = 1.0 / r.rate;
      joint_states_.push_back(std::move(s));
      it = std::prev(joint_states_.end());
    } else {
      ROS_INFO_STREAM(r.topic << ": " << r.source
                              << " shares the topic with another joint state source: merged "
                                 "into one stream at the higher rate");
      it->schedule.period = std::min(it->schedule.period, 1.0 / r.rate);
    }
    for (const std::string& j : r.joints) {
      const int idx = pr.jointIndex(j);
      if (idx < 0) throw ModelError(r.source + ": joint '" + j + "' is not a movable joint");
      if (std::find(it->joints.begin(), it->joints.end(), idx) == it->joints.end()) {
        it->joints.push_back(idx);
        it->msg.name.push_back(j);
      }
    }
  }
  for (JointStateStream& s : joint_states_) {
    s.msg.position.resize(s.joints.size());
    s.msg.velocity.resize(s.joints.size());
    s.msg.effort.resize(s.joints.size());
    ROS_INFO_STREAM(s.pub.getTopic() << ": " << s.joints.size() << " joints at "
                                     << 1.0 / s.schedule.period << " Hz");
  }
}

void RobotBridge::publish(double t) {
  const ros::Time stamp(t);
  const PhysicsRobot& pr = sim_.simulation().physics().robot(sim_.robot(id_)->id);
  for (JointStateStream& s : joint_states_) {
    if (!s.schedule.due(t) || s.pub.getNumSubscribers() == 0) continue;
    s.msg.header.stamp = stamp;
    for (size_t k = 0; k < s.joints.size(); ++k) {
      s.msg.position[k] = pr.jointPosition(s.joints[k]);
      s.msg.velocity[k] = pr.jointVelocity(s.joints[k]);
      s.msg.effort[k] = pr.jointEffort(s.joints[k]);
    }
    s.pub.publish(s.msg);
  }
  if (ground_truth_schedule_.due(t) && ground_truth_.getNumSubscribers() > 0) {
    ground_truth_.publish(
        toGroundTruth(pr.basePose(), pr.baseTwist(), stamp, "world", base_frame_));
  }
}

void RobotBridge::restart(double t) {
  for (JointStateStream& s : joint_states_) s.schedule.restart(t);
  ground_truth_schedule_.restart(t);
}

}  // namespace tianracer_sim
