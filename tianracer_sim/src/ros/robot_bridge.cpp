#include "tianracer_sim/ros/robot_bridge.h"

#include <algorithm>
#include <optional>

#include <geometry_msgs/TransformStamped.h>
#include <nav_msgs/Odometry.h>
#include <std_msgs/Bool.h>

#include <tianracer_control/naming.h>

#include "tianracer_sim/plugins/sensor_topics.h"
#include "tianracer_sim/ros/state_msgs.h"

namespace tianracer_sim {

namespace tc = tianracer_control;

namespace {
const std::string kWorldFrame = "world";
}  // namespace

RobotBridge::RobotBridge(Simulator& sim, ModelId id, Options options, ros::NodeHandle root,
                         tf2_ros::StaticTransformBroadcaster& static_tf)
    : sim_(sim), id_(id), options_(std::move(options)), root_(root) {
  SimRobot& robot = *sim_.robot(id_);
  physics_id_ = robot.id;
  const Entities entities = sim_.entities();
  base_frame_ = tc::resolveFrame(options_.tf_prefix, entities.bodyLinks(id_).front());

  // world -> odom at the spawn pose: wheel odometry starts there, so rviz can show the
  // ground truth (world) and the odometry (odom) together.
  if (!options_.odom_frame.empty()) {
    geometry_msgs::TransformStamped tf;
    tf.header.frame_id = "world";
    tf.child_frame_id = tc::resolveFrame(options_.tf_prefix, options_.odom_frame);
    const geometry_msgs::Pose p = toPose(entities.spawnPose(id_));
    tf.transform.translation.x = p.position.x;
    tf.transform.translation.y = p.position.y;
    tf.transform.translation.z = p.position.z;
    tf.transform.rotation = p.orientation;
    static_tf.sendTransform(tf);
  }

  if (StepProfile* p = sim_.profile()) {
    rows_.joint_states = p->row(kProfileRows[0]);
    rows_.joint_states_convert = p->row(kProfileRows[1]);
    rows_.joint_states_send = p->row(kProfileRows[2]);
    rows_.ground_truth = p->row(kProfileRows[3]);
    rows_.ground_truth_convert = p->row(kProfileRows[4]);
    rows_.ground_truth_send = p->row(kProfileRows[5]);
  }
  joint_states_ = makeJointStates();
  ros::NodeHandle robot_nh(root, options_.ns);
  commands_ = std::make_shared<tc::ControllerCommandSubscribers>(robot_nh, robot.controllers);
  ground_truth_ = robot_nh.advertise<nav_msgs::Odometry>("ground_truth/odom", 10);
  ground_truth_schedule_.period =
      options_.ground_truth_rate > 0.0 ? 1.0 / options_.ground_truth_rate : 0.0;
  // GazeboRosControlPlugin::Load: model_nh_.subscribe(eStopTopic, 1, eStopCB).
  if (!options_.e_stop_topic.empty()) {
    e_stop_ = std::make_shared<std::atomic<bool>>(false);
    auto flag = e_stop_;
    e_stop_sub_ = robot_nh.subscribe<std_msgs::Bool>(
        options_.e_stop_topic, 1, [flag](const std_msgs::BoolConstPtr& m) { *flag = m->data; });
  }
  if (options_.controller_manager) {
    controller_manager_ = std::make_unique<ControllerManagerBridge>(
        robot_nh, options_.control_ns, sim_, id_, [this] { controllersChanged(); });
  }
}

void RobotBridge::applyCommands() {
  commands_->apply();
  if (e_stop_) {
    if (SimRobot* robot = sim_.robot(id_)) robot->hw_sim.setEStop(*e_stop_);
  }
}

void RobotBridge::controllersChanged() {
  // The new subscribers and publishers exist before the old ones go, so that connections on
  // the topics that stay are kept. A stream that stays keeps its schedule.
  ros::NodeHandle robot_nh(root_, options_.ns);
  // The sides of the controllers still loaded are taken over (their topics and services stay).
  commands_ = std::make_shared<tc::ControllerCommandSubscribers>(
      robot_nh, sim_.robot(id_)->controllers, commands_.get());
  std::vector<JointStateStream> streams = makeJointStates();
  for (JointStateStream& s : streams) {
    for (const JointStateStream& old : joint_states_) {
      if (old.pub.getTopic() == s.pub.getTopic()) s.schedule.next = old.schedule.next;
    }
  }
  joint_states_.swap(streams);
  if (options_.controllers_changed) options_.controllers_changed();
}

std::vector<RobotBridge::JointStateStream> RobotBridge::makeJointStates() {
  // Both the joint_state_publisher plugin and joint_state_controller publish JointState; when
  // they resolve to the same topic they become ONE stream (one publisher): the plugin's joints
  // in its order, then the controller's other joints, at the higher of the two rates.
  struct Request {
    std::string topic;
    std::vector<std::string> joints;
    double rate;
    std::string source;
    bool from_handles = false;  // joints[n] is robot.handles[n], the state the hardware's
  };
  std::vector<Request> requests;
  const SimRobot& robot = *sim_.robot(id_);
  const RobotModel& model = robot.model;
  if (const auto& jsp = model.ext.joint_state_publisher) {
    requests.push_back({resolveTopic(jsp->robot_namespace, "joint_states"), jsp->joint_names,
                        jsp->update_rate, "joint_state_publisher plugin"});
  }
  for (const auto& c : robot.controllers.controllers()) {
    if (!robot.controllers.isRunning(*c)) continue;
    if (auto* jsc = dynamic_cast<const tc::JointStateController*>(c.get())) {
      std::vector<std::string> joints;
      for (const auto& h : robot.handles) joints.push_back(h.name);
      requests.push_back({resolveTopic(options_.ns, "joint_states"), joints, jsc->publishRate(),
                          "joint_state_controller '" + c->name() + "'",
                          robot.steer_bot.has_value()});
    }
  }
  std::vector<JointStateStream> streams;
  for (const Request& r : requests) {
    auto it = std::find_if(streams.begin(), streams.end(),
                           [&](const JointStateStream& s) { return s.pub.getTopic() == r.topic; });
    if (it == streams.end()) {
      JointStateStream s;
      s.pub = root_.advertise<sensor_msgs::JointState>(r.topic, 10);
      s.schedule.period = 1.0 / r.rate;
      streams.push_back(std::move(s));
      it = std::prev(streams.end());
    } else {
      ROS_INFO_STREAM(r.topic << ": " << r.source
                              << " shares the topic with another joint state source: merged "
                                 "into one stream at the higher rate");
      it->schedule.period = std::min(it->schedule.period, 1.0 / r.rate);
    }
    for (size_t n = 0; n < r.joints.size(); ++n) {
      const std::string& j = r.joints[n];
      const int idx = sim_.jointIndex(id_, j, nullptr, nullptr);
      const int handle = r.from_handles ? static_cast<int>(n) : -1;
      if (idx < 0 && handle < 0) throw ModelError(r.source + ": joint '" + j + "' is not a movable joint");
      if (std::find(it->msg.name.begin(), it->msg.name.end(), j) == it->msg.name.end()) {
        it->joints.push_back(idx);
        it->handles.push_back(handle);
        it->msg.name.push_back(j);
      }
    }
  }
  for (JointStateStream& s : streams) {
    s.msg.position.resize(s.joints.size());
    s.msg.velocity.resize(s.joints.size());
    s.msg.effort.resize(s.joints.size());
    ROS_INFO_STREAM(s.pub.getTopic() << ": " << s.joints.size() << " joints at "
                                     << 1.0 / s.schedule.period << " Hz");
  }
  return streams;
}

void RobotBridge::publish(double t) {
  StepProfile* const profile = sim_.profile();
  const ros::Time stamp(t);
  const Entities entities = sim_.entities();
  const std::vector<tc::JointHandle>& handles = sim_.robot(id_)->handles;
  commands_->publish(t);  // what the controllers produced (diff_drive_controller's odom, tf)
  {
    StepProfile::Scope timed(profile, rows_.joint_states);
    for (JointStateStream& s : joint_states_) {
      if (!s.schedule.due(t) || s.pub.getNumSubscribers() == 0) continue;
      {
        StepProfile::Scope part(profile, rows_.joint_states_convert);
        s.msg.header.stamp = stamp;
        for (size_t k = 0; k < s.joints.size(); ++k) {
          if (s.handles[k] >= 0) {
            const tc::JointHandle& h = handles[s.handles[k]];
            s.msg.position[k] = h.position;
            s.msg.velocity[k] = h.velocity;
            s.msg.effort[k] = h.effort;
            continue;
          }
          const JointReading j = entities.jointReading(id_, s.joints[k]);
          s.msg.position[k] = j.position;
          s.msg.velocity[k] = j.velocity;
          s.msg.effort[k] = j.effort;
        }
      }
      StepProfile::Scope part(profile, rows_.joint_states_send);
      s.pub.publish(s.msg);
    }
  }
  StepProfile::Scope timed(profile, rows_.ground_truth);
  if (ground_truth_schedule_.due(t) && ground_truth_.getNumSubscribers() > 0) {
    std::optional<StepProfile::Scope> part(std::in_place, profile, rows_.ground_truth_convert);
    const EntityState base = sim_.modelState(id_);
    toGroundTruth(base.X_WE, base.V_WE, stamp, kWorldFrame, base_frame_, &ground_truth_msg_);
    part.emplace(profile, rows_.ground_truth_send);
    ground_truth_.publish(ground_truth_msg_);
  }
}

void RobotBridge::restart(double t) {
  for (JointStateStream& s : joint_states_) s.schedule.restart(t);
  ground_truth_schedule_.restart(t);
}

}  // namespace tianracer_sim
