#include "tianracer_sim/ros/lockstep.h"

#include <algorithm>
#include <cmath>
#include <sstream>
#include <stdexcept>

#include <topic_tools/shape_shifter.h>

namespace tianracer_sim {

namespace {

std::vector<std::string> topicList(const ros::NodeHandle& pnh, const std::string& key) {
  std::vector<std::string> names;
  XmlRpc::XmlRpcValue v;
  if (!pnh.getParam(key, v)) return names;
  const auto bad = [&] {
    return std::runtime_error("parameter " + pnh.resolveName(key) +
                              " must be a list of topics or a space-separated string, got " + v.toXml());
  };
  if (v.getType() == XmlRpc::XmlRpcValue::TypeString) {
    std::istringstream in(static_cast<std::string>(v));
    for (std::string n; in >> n;) names.push_back(n);
  } else if (v.getType() == XmlRpc::XmlRpcValue::TypeArray) {
    for (int i = 0; i < v.size(); ++i) {
      if (v[i].getType() != XmlRpc::XmlRpcValue::TypeString) throw bad();
      names.push_back(static_cast<std::string>(v[i]));
    }
  } else {
    throw bad();
  }
  return names;
}

double positive(const ros::NodeHandle& pnh, const std::string& key, double fallback) {
  XmlRpc::XmlRpcValue v;
  if (!pnh.getParam(key, v)) return fallback;
  double x = NAN;
  if (v.getType() == XmlRpc::XmlRpcValue::TypeDouble) x = static_cast<double>(v);
  if (v.getType() == XmlRpc::XmlRpcValue::TypeInt) x = static_cast<int>(v);
  if (!(x > 0.0) || !std::isfinite(x)) {
    throw std::runtime_error("parameter " + pnh.resolveName(key) + " must be a number > 0, got " +
                             v.toXml());
  }
  return x;
}

}  // namespace

LockstepOptions lockstepOptions(const ros::NodeHandle& pnh) {
  LockstepOptions o;
  o.replies = topicList(pnh, "lockstep/replies");
  for (const std::string& t : topicList(pnh, "lockstep/ticks")) {
    if (t == "commands") {
      o.tick_commands = true;
    } else {
      o.ticks.push_back(t);
    }
  }
  o.reply_period = positive(pnh, "lockstep/reply_period", o.reply_period);
  o.tick_period = positive(pnh, "lockstep/tick_period", o.tick_period);
  o.timeout = positive(pnh, "lockstep/timeout", o.timeout);
  return o;
}

Lockstep::Lockstep(ros::NodeHandle nh, ros::CallbackQueue* queue, LockstepOptions options)
    : nh_(nh), queue_(queue), options_(std::move(options)) {
  nh_.setCallbackQueue(queue_);
  subscribe(nh_, options_.replies, &replies_);
  subscribe(nh_, options_.ticks, &ticks_);
}

std::unique_ptr<Lockstep::Topic> Lockstep::makeTopic(ros::NodeHandle& nh, const std::string& name) {
  auto topic = std::make_unique<Topic>();
  topic->name = nh.resolveName(name);
  Topic* raw = topic.get();
  // Any type: only the arrival matters. tcp_nodelay, as the answer is awaited.
  topic->sub = nh.subscribe<topic_tools::ShapeShifter>(
      topic->name, 10,
      [raw](const topic_tools::ShapeShifter::ConstPtr&) {
        raw->arrived = true;
        raw->absent = false;
      },
      ros::VoidConstPtr(), ros::TransportHints().tcpNoDelay());
  return topic;
}

void Lockstep::subscribe(ros::NodeHandle& nh, const std::vector<std::string>& names, Group* group) {
  for (const std::string& name : names) group->push_back(makeTopic(nh, name));
}

void Lockstep::setCommandTopics(const std::vector<std::string>& topics) {
  if (!options_.tick_commands) return;
  std::vector<std::string> wanted;
  for (const std::string& t : topics) wanted.push_back(nh_.resolveName(t));
  // Gone: command topics no longer wanted (topics named in ~lockstep/ticks stay).
  ticks_.erase(std::remove_if(ticks_.begin(), ticks_.end(),
                              [&](const std::unique_ptr<Topic>& topic) {
                                return topic->command && std::find(wanted.begin(), wanted.end(),
                                                                   topic->name) == wanted.end();
                              }),
               ticks_.end());
  for (const std::string& name : wanted) {
    const bool known = std::any_of(ticks_.begin(), ticks_.end(), [&](const auto& topic) {
      return topic->name == name;
    });
    if (known) continue;
    std::unique_ptr<Topic> topic = makeTopic(nh_, name);
    topic->command = true;
    // At start-up everything is waited for from the first tick; later a new controller's topic
    // only once somebody publishes there.
    topic->absent = started_;
    ticks_.push_back(std::move(topic));
  }
  started_ = true;
}

std::vector<std::string> Lockstep::tickTopics() const {
  std::vector<std::string> names;
  for (const auto& topic : ticks_) names.push_back(topic->name);
  return names;
}

void Lockstep::mark(Group& group) {
  queue_->callAvailable(ros::WallDuration(0.0));  // what already came answers an earlier step
  for (auto& topic : group) {
    topic->arrived = false;
    // A new publisher (a node started mid-run) is waited for from this tick on: its sim-time
    // timer started on the tick grid (clockOnTicksOnly()) ticks here.
    const std::uint32_t publishers = topic->sub.getNumPublishers();
    if (publishers > topic->publishers) topic->absent = false;
    topic->publishers = publishers;
  }
}

void Lockstep::await(Group& group, double t, const char* after) {
  const ros::WallTime deadline = ros::WallTime::now() + ros::WallDuration(options_.timeout);
  while (ros::ok()) {
    bool all = true;
    for (const auto& topic : group) {
      all = all && (topic->arrived || topic->absent || topic->sub.getNumPublishers() == 0);
    }
    if (all) return;
    const ros::WallTime now = ros::WallTime::now();
    if (now >= deadline) break;
    queue_->callAvailable(std::min(deadline - now, ros::WallDuration(0.01)));
  }
  for (auto& topic : group) {
    if (topic->arrived || topic->absent || topic->sub.getNumPublishers() == 0) continue;
    topic->absent = true;
    ++timeouts_;
    if (!topic->reported) {
      ROS_WARN("lockstep: nothing on %s within %g s (wall) after %s sim time %.3f s: going on "
               "without it until its next message (reported once per topic)",
               topic->name.c_str(), options_.timeout, after, t);
      topic->reported = true;
    }
  }
}

}  // namespace tianracer_sim
