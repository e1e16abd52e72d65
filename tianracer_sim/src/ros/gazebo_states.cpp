// gazebo_ros's state services and topics (gazebo_ros/src/gazebo_ros_api_plugin.cpp,
// noetic-devel) over the Simulator's one name resolver (simulator/entities.h):
// get/set_model_state, get/set_link_state and their set_*_state topics, get_model_properties,
// get_world_properties, and the /gazebo/model_states and /gazebo/link_states messages.
#include <map>

#include "gazebo_answer.h"
#include "tianracer_sim/ros/gazebo_interface.h"
#include "tianracer_sim/ros/state_msgs.h"

namespace tianracer_sim {

namespace {

EntityState stateFromMsg(const geometry_msgs::Pose& pose, const geometry_msgs::Twist& twist,
                         bool* ok) {
  EntityState s;
  *ok = fromPose(pose, &s.X_WE) && fromTwistMsg(twist, &s.V_WE);
  return s;
}

}  // namespace

// --- model and link states ----------------------------------------------------------------------

bool GazeboInterface::getModelState(gazebo_msgs::GetModelState::Request& req,
                                    gazebo_msgs::GetModelState::Response& res) {
  res.header.stamp = ros::Time(simulator_.time());
  res.header.frame_id = req.relative_entity_name;
  res.success = false;
  const Target t = target(req.model_name, true, req.relative_entity_name);
  if (!t.ok) {
    res.status_message = "get_model_state: " + t.error;
    return true;
  }
  if (!t.entity.link.empty()) {
    res.status_message = "get_model_state: '" + req.model_name +
                         "' is a link; use get_link_state or the model's name";
    return true;
  }
  const EntityState s = relativeTo(entities_.state(t.entity), t.frame);
  res.pose = toPose(s.X_WE);
  res.twist = toTwistMsg(s.V_WE);
  return succeeded(res, "GetModelState: got properties");
}

bool GazeboInterface::setModelState(gazebo_msgs::SetModelState::Request& req,
                                    gazebo_msgs::SetModelState::Response& res) {
  const gazebo_msgs::ModelState& m = req.model_state;
  return answer(res, {"set_model_state: "}, [&] {
    const Target t = target(m.model_name, true, m.reference_frame);
    if (!t.ok) throw InputError(t.error);
    if (!t.entity.link.empty())
      throw InputError("'" + m.model_name + "' is a link; use set_link_state");
    if (!t.entity.body)
      throw InputError("model '" + m.model_name + "' is static and cannot be moved");
    EntityState in_frame;
    if (!fromPose(m.pose, &in_frame.X_WE)) {
      throw InputError("pose of '" + m.model_name +
                       "' is not finite or has a zero quaternion; state unchanged");
    }
    if (!fromTwistMsg(m.twist, &in_frame.V_WE))
      throw InputError("twist of '" + m.model_name + "' is not finite; state unchanged");
    try {
      entities_.setBase(t.entity, fromFrame(in_frame, t.frame), true);
    } catch (const InputError& e) {
      throw InputError(std::string(e.what()) + " for '" + m.model_name + "'; state unchanged");
    }
    return "SetModelState: set model state done";
  });
}

bool GazeboInterface::getLinkState(gazebo_msgs::GetLinkState::Request& req,
                                   gazebo_msgs::GetLinkState::Response& res) {
  res.success = false;
  res.link_state.link_name = req.link_name;
  res.link_state.reference_frame = req.reference_frame;
  const Target t = target(req.link_name, false, req.reference_frame);
  if (!t.ok) {
    res.status_message = "get_link_state: " + t.error;
    return true;
  }
  const EntityState s = relativeTo(entities_.state(t.entity), t.frame);
  res.link_state.pose = toPose(s.X_WE);
  res.link_state.twist = toTwistMsg(s.V_WE);
  return succeeded(res, "GetLinkState: got state");
}

bool GazeboInterface::setLinkState(gazebo_msgs::SetLinkState::Request& req,
                                   gazebo_msgs::SetLinkState::Response& res) {
  const gazebo_msgs::LinkState& l = req.link_state;
  bool finite = false;
  const EntityState in_frame = stateFromMsg(l.pose, l.twist, &finite);
  return answer(res, {"set_link_state: "}, [&] {
    const Target t = target(l.link_name, false, l.reference_frame);
    if (!t.ok) throw InputError(t.error);
    if (!t.entity.body)
      throw InputError("'" + l.link_name + "' belongs to a static model and cannot be moved");
    if (!finite) {
      throw InputError("pose or twist of '" + l.link_name +
                       "' is not finite or has a zero quaternion; state unchanged");
    }
    // The whole robot moves rigidly so that the link gets the state (joints kept): gazebo
    // moves the one link and lets the joints pull the others after it.
    const EntityState B = entities_.baseFor(t.entity, fromFrame(in_frame, t.frame));
    try {
      entities_.setBase(t.entity, B, false);
    } catch (const InputError& e) {
      throw InputError(std::string(e.what()) + " for '" + l.link_name +
                       "' (its model's base); state unchanged");
    }
    return "SetLinkState: success";
  });
}

void GazeboInterface::onModelStateTopic(const gazebo_msgs::ModelState::ConstPtr& msg) {
  gazebo_msgs::SetModelState::Request req;
  gazebo_msgs::SetModelState::Response res;
  req.model_state = *msg;
  setModelState(req, res);  // a failure is logged there
}

void GazeboInterface::onLinkStateTopic(const gazebo_msgs::LinkState::ConstPtr& msg) {
  gazebo_msgs::SetLinkState::Request req;
  gazebo_msgs::SetLinkState::Response res;
  req.link_state = *msg;
  setLinkState(req, res);
}

// --- properties ---------------------------------------------------------------------------------

bool GazeboInterface::getModelProperties(gazebo_msgs::GetModelProperties::Request& req,
                                         gazebo_msgs::GetModelProperties::Response& res) {
  res.success = false;
  Entity e;
  try {
    e = entities_.find(req.model_name, true);
    if (!e.link.empty()) throw InputError("'" + req.model_name + "' is a link, not a model");
  } catch (const InputError& error) {
    res.status_message = "get_model_properties: " + std::string(error.what());
    return true;
  }
  if (e.robot) {
    // Bodies as Gazebo's URDF import makes them: links joined by fixed joints are lumped into
    // their parent, and the lumped collisions are named <parent>_fixed_joint_lump__<link>_collision.
    const std::vector<TreeBody>& bodies = entities_.bodies(e);
    for (const TreeBody& b : bodies) {
      res.body_names.push_back(b.link);
      std::map<std::string, int> count;
      for (const CollisionGeometry& c : b.collisions) {
        std::string name = c.link == b.link ? c.link + "_collision"
                                             : b.link + "_fixed_joint_lump__" + c.link + "_collision";
        const int k = count[name]++;
        if (k > 0) name += "_" + std::to_string(k);
        res.geom_names.push_back(name);
      }
    }
    for (const JointInfo& j : entities_.joints(e)) res.joint_names.push_back(j.name);
    res.canonical_body_name = bodies.front().link;
    res.is_static = false;
  } else if (e.ground_plane) {
    res.body_names = {"link"};
    res.geom_names = {"collision"};
    res.canonical_body_name = "link";
    res.is_static = true;
  } else {
    for (const LinkDescription& l : e.model->links) {
      res.body_names.push_back(l.name);
      for (const CollisionDescription& c : l.collisions) res.geom_names.push_back(c.name);
    }
    if (!e.model->links.empty()) res.canonical_body_name = e.model->links.front().name;
    res.is_static = e.body == nullptr;
  }
  return succeeded(res, "GetModelProperties: got properties");
}

bool GazeboInterface::getWorldProperties(gazebo_msgs::GetWorldProperties::Request&,
                                         gazebo_msgs::GetWorldProperties::Response& res) {
  res.sim_time = simulator_.time();
  res.model_names = entities_.modelNames();
  res.rendering_enabled = true;
  return succeeded(res, "GetWorldProperties: got properties");
}

void GazeboInterface::rebuildStateMessages() {
  model_states_.name.clear();
  model_states_.pose.clear();
  model_slots_ = entities_.models();
  link_states_.name.clear();
  link_states_.pose.clear();
  link_slots_ = entities_.links();
  for (const Entity& e : model_slots_) {
    model_states_.name.push_back(e.model_name);
    model_states_.pose.push_back(toPose(entities_.state(e).X_WE));
  }
  for (const Entity& e : link_slots_) {
    link_states_.name.push_back(e.model_name + "::" + e.link);
    link_states_.pose.push_back(toPose(entities_.state(e).X_WE));
  }
  msgs_valid_ = true;
  model_states_.twist.assign(model_states_.name.size(), geometry_msgs::Twist());
  link_states_.twist.assign(link_states_.name.size(), geometry_msgs::Twist());
  msgs_models_version_ = simulator_.modelsVersion();
}

void GazeboInterface::afterStep() {
  // The ground truth's schedule (sim_node's Schedule): a fixed grid, restarted after a pause
  // or reset rather than bursting to catch up.
  const double t = simulator_.time();
  if (t + 1e-9 < next_) return;
  if (period_ > 0.0) {
    next_ += period_;
    if (next_ <= t) next_ = t + period_;
  } else {
    next_ = t;
  }
  const bool want_models = model_states_pub_.getNumSubscribers() > 0;
  const bool want_links = link_states_pub_.getNumSubscribers() > 0;
  if (!want_models && !want_links) return;
  if (!msgs_valid_ || msgs_models_version_ != simulator_.modelsVersion()) rebuildStateMessages();
  if (want_models) {
    for (std::size_t i = 0; i < model_slots_.size(); ++i) {
      if (!model_slots_[i].moves()) continue;
      const EntityState s = entities_.state(model_slots_[i]);
      model_states_.pose[i] = toPose(s.X_WE);
      model_states_.twist[i] = toTwistMsg(s.V_WE);
    }
    model_states_pub_.publish(model_states_);
  }
  if (want_links) {
    for (std::size_t i = 0; i < link_slots_.size(); ++i) {
      if (!link_slots_[i].moves()) continue;
      const EntityState s = entities_.state(link_slots_[i]);
      link_states_.pose[i] = toPose(s.X_WE);
      link_states_.twist[i] = toTwistMsg(s.V_WE);
    }
    link_states_pub_.publish(link_states_);
  }
}

}  // namespace tianracer_sim
