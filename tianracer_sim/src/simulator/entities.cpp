#include "tianracer_sim/simulator/entities.h"

#include <algorithm>
#include <stdexcept>

#include <urdf_model/model.h>

#include "tianracer_sim/common/diagnostic.h"
#include "tianracer_sim/simulator/simulator.h"

namespace tianracer_sim {

Entity Entities::find(const std::string& name, bool allow_model) const {
  const ScopedName n = splitScopedName(name);
  Entity e;
  e.model_name = n.model;
  e.link = n.link;
  if (n.model.empty()) {
    throw InputError("'" + name + "' names no model (use \"model\" or \"model::link\")");
  }
  if (n.link.empty() && !allow_model) {
    throw InputError("'" + name + "' is not a link: use gazebo's scoped name \"model::link\"");
  }
  const WorldDescription& world = sim_.world();
  e.id = sim_.findModel(n.model);
  if (const SimRobot* robot = sim_.robot(e.id)) {
    e.robot = robot;
    e.body = sim_.physicsOf(e.id);
    if (!n.link.empty() && !robot->model.urdf->getLink(n.link)) {
      throw InputError("model '" + n.model + "' has no link '" + n.link + "'");
    }
    return e;
  }
  if (world.ground_plane && n.model == "ground_plane") {
    e.ground_plane = true;
    if (!n.link.empty() && n.link != "link") {
      throw InputError("model 'ground_plane' has no link '" + n.link + "' (its one link is 'link')");
    }
    return e;
  }
  for (const ModelDescription& m : world.models) {
    if (m.name != n.model) continue;
    e.model = &m;
    if (e.id != kNoModel) e.body = sim_.physicsOf(e.id);
    if (!n.link.empty() &&
        std::none_of(m.links.begin(), m.links.end(),
                     [&](const LinkDescription& l) { return l.name == n.link; })) {
      throw InputError("model '" + n.model + "' has no link '" + n.link + "'");
    }
    return e;
  }
  for (const ActorDescription& a : world.actors) {
    if (a.model.name != n.model) continue;
    e.model = &a.model;
    e.actor = true;
    if (!n.link.empty() &&
        std::none_of(a.model.links.begin(), a.model.links.end(),
                     [&](const LinkDescription& l) { return l.name == n.link; })) {
      throw InputError("actor '" + n.model + "' has no link '" + n.link + "'");
    }
    return e;
  }
  std::string known;
  for (const std::string& m : modelNames()) known += (known.empty() ? "" : ", ") + m;
  throw InputError("no model named '" + n.model + "' (models: " + known + ")");
}

EntityState Entities::state(const Entity& e) const {
  EntityState s;
  if (const PhysicsRobot* body = e.body) {
    if (e.link.empty()) {
      s.X_WE = body->basePose();
      s.V_WE = body->baseTwist();
    } else {
      s.X_WE = body->linkPose(e.link);
      s.V_WE = body->linkTwist(e.link);
    }
  } else if (e.ground_plane) {
    s.X_WE = sim_.world().X_WG;
  } else if (e.actor && e.id != kNoModel) {
    // Where its script has put it (velocity 0, as Gazebo's SetWorldPose leaves its links).
    s.X_WE = e.link.empty() ? sim_.modelState(e.id).X_WE : sim_.linkPose({e.id, e.link});
  } else if (e.model) {
    s.X_WE = e.model->X_WM;
    for (const LinkDescription& l : e.model->links) {
      if (!e.link.empty() && l.name == e.link) s.X_WE = e.model->X_WM * l.X_ML;
    }
  }
  return s;
}

EntityState Entities::frame(const std::string& reference_frame) const {
  if (isWorldFrame(reference_frame)) return EntityState();
  try {
    return state(find(reference_frame, true));
  } catch (const InputError& e) {
    throw InputError("reference_frame: " + std::string(e.what()));
  }
}

void Entities::setBase(const Entity& e, const EntityState& base, bool stop_joints) const {
  if (e.actor) throw InputError("'" + e.model_name + "' is an actor: its <script> moves it");
  if (!e.body) throw InputError("model '" + e.model_name + "' is static and cannot be moved");
  if (const std::string bad = checkModelState(base.X_WE, base.V_WE); !bad.empty()) {
    throw InputError(bad);
  }
  e.body->setBasePose(base.X_WE);
  if (stop_joints) {
    e.body->setModelTwist(base.V_WE);
  } else {
    e.body->setBaseTwist(base.V_WE);
  }
}

JointRef Entities::joint(const std::string& name) const {
  const ScopedName n = splitScopedName(name);
  // "joint" alone: n.model holds it and n.link is empty.
  const std::string joint = n.link.empty() ? n.model : n.link;
  const std::string model = n.link.empty() ? "" : n.model;
  if (joint.empty()) throw InputError("joint '" + name + "': no joint name given");
  bool model_found = model.empty();
  for (const ModelId id : sim_.modelIds()) {
    if (!model.empty() && sim_.modelName(id) != model) continue;
    model_found = true;
    PhysicsRobot* body = sim_.physicsOf(id);
    if (!body) continue;  // a static model: its joints do not move
    const int i = body->jointIndex(joint);
    if (i >= 0) return {body, i};
  }
  if (!model_found) throw InputError("joint '" + name + "': no model named '" + model + "'");
  throw InputError("joint '" + name + "' not found: no " +
                   (model.empty() ? std::string("model") : "model '" + model + "'") +
                   " has a movable joint of that name (fixed joints are merged into their parent)");
}

std::vector<std::string> Entities::modelNames() const {
  std::vector<std::string> names;
  for (const Entity& e : models()) names.push_back(e.model_name);
  return names;
}

std::vector<Entity> Entities::models() const {
  std::vector<Entity> out;
  const WorldDescription& world = sim_.world();
  if (world.ground_plane) {
    Entity e;
    e.ground_plane = true;
    e.model_name = "ground_plane";
    out.push_back(e);
  }
  for (const ModelDescription& m : world.models) {
    Entity e;
    e.id = sim_.findModel(m.name);
    e.model = &m;
    if (e.id != kNoModel) e.body = sim_.physicsOf(e.id);
    e.model_name = m.name;
    out.push_back(e);
  }
  for (const ActorDescription& a : world.actors) {
    Entity e;
    e.id = sim_.findModel(a.model.name);
    if (e.id == kNoModel) continue;  // deleted
    e.model = &a.model;
    e.actor = true;
    e.model_name = a.model.name;
    out.push_back(e);
  }
  for (const ModelId id : sim_.robotIds()) {
    Entity e;
    e.id = id;
    e.robot = sim_.robot(id);
    e.body = sim_.physicsOf(id);
    e.model_name = sim_.modelName(id);
    out.push_back(e);
  }
  return out;
}

std::vector<Entity> Entities::links() const {
  std::vector<Entity> out;
  for (Entity e : models()) {
    if (e.ground_plane) {
      e.link = "link";
      out.push_back(e);
    } else if (e.robot) {
      for (const std::string& link : bodyLinks(e.id)) {
        e.link = link;
        out.push_back(e);
      }
    } else if (e.model) {
      // Every link, as Gazebo lists a world model's links (each moves on its own).
      for (const LinkDescription& l : e.model->links) {
        e.link = l.name;
        out.push_back(e);
      }
    }
  }
  return out;
}

std::vector<std::string> Entities::bodyLinks(ModelId id) const {
  std::vector<std::string> links;
  if (const PhysicsRobot* body = sim_.physicsOf(id)) {
    for (const TreeBody& b : body->tree().bodies) links.push_back(b.link);
  }
  return links;
}

Eigen::Isometry3d Entities::spawnPose(ModelId id) const {
  const PhysicsRobot* body = sim_.physicsOf(id);
  if (!body) throw std::out_of_range("model '" + sim_.modelName(id) + "' is static: it was not spawned");
  return body->spawnPose();
}

JointReading Entities::jointReading(ModelId id, int joint) const {
  const PhysicsRobot& body = *sim_.physicsOf(id);
  return {body.jointPosition(joint), body.jointVelocity(joint), body.jointEffort(joint)};
}

EntityState Entities::baseFor(const Entity& link, const EntityState& L) const {
  if (!link.body) throw InputError("'" + link.model_name + "::" + link.link + "' belongs to a static model");
  const PhysicsRobot& pr = *link.body;
  const Eigen::Isometry3d X_LB = pr.linkPose(link.link).inverse() * pr.basePose();
  EntityState B;
  B.X_WE = L.X_WE * X_LB;
  B.V_WE = shiftTwist(L.V_WE, L.X_WE.translation(), B.X_WE.translation());
  return B;
}

void Entities::applyWrench(const Entity& link, const Eigen::Vector3d& force_W,
                           const Eigen::Vector3d& torque_W) const {
  if (link.body) link.body->setExternalWrench(link.link, force_W, torque_W);
}

void Entities::applyJointEffort(const JointRef& joint, double effort) const {
  joint.body->setJointExternalEffort(joint.index, effort);
}

const std::vector<TreeBody>& Entities::bodies(const Entity& e) const {
  static const std::vector<TreeBody> none;
  return e.body ? e.body->tree().bodies : none;
}

const std::vector<JointInfo>& Entities::joints(const Entity& e) const {
  static const std::vector<JointInfo> none;
  return e.body ? e.body->joints() : none;
}

}  // namespace tianracer_sim
