#include "tianracer_sim/sim/world_physics.h"

#include <functional>
#include <map>
#include <set>
#include <string>

#include "tianracer_sim/physics/mass_properties.h"

namespace tianracer_sim {

namespace {

/// A model fixed to the world by a joint does not move (Gazebo).
bool fixedToWorld(const ModelDescription& model) {
  for (const JointDescription& j : model.joints) {
    if (j.parent == "world" || j.child == "world") return true;
  }
  return false;
}

std::string at(const WorldDescription& world, int line) {
  return world.source + ":" + std::to_string(line) + ": ";
}

}  // namespace

PhysicsOptions physicsOptionsFor(const WorldDescription& world, PhysicsOptions base) {
  base.dt = world.physics.max_step_size;
  base.gravity = world.physics.gravity;
  base.ground_plane = world.ground_plane;
  base.ground_mu = world.ground_friction.mu;
  base.ground_mu2 = world.ground_friction.mu2;
  return base;
}

SurfaceParams surfaceOf(const CollisionDescription& c) {
  SurfaceParams s;
  s.mu1 = c.friction.mu;
  s.mu2 = c.friction.mu2;
  if (c.contact.kp) s.kp = *c.contact.kp;
  if (c.contact.kd) s.kd = *c.contact.kd;
  s.max_vel = c.contact.max_vel;
  if (c.contact.min_depth) s.min_depth = *c.contact.min_depth;
  return s;
}

RigidTree freeBodyTree(const WorldDescription& world, const ModelDescription& model,
                       std::vector<SurfaceParams>* surfaces, const WarningSink& warn) {
  auto warnAt = [&](int line, const std::string& message) {
    if (warn) warn(at(world, line) + "model '" + model.name + "': " + message);
  };
  // Links reached from the first one through joints; the others are warned about.
  std::set<std::string> joined;
  if (!model.links.empty()) joined.insert(model.links.front().name);
  for (bool grew = true; grew;) {
    grew = false;
    for (const JointDescription& j : model.joints) {
      if (joined.count(j.parent) != joined.count(j.child)) {
        joined.insert(joined.count(j.parent) ? j.child : j.parent);
        grew = true;
      }
    }
  }
  for (const JointDescription& j : model.joints) {
    if (j.type != "fixed") {
      warnAt(j.line, "joint '" + j.name + "' (" + j.type +
                         ") is held fixed: a dynamic world model moves as one rigid body");
    }
  }
  for (const LinkDescription& l : model.links) {
    if (!joined.count(l.name)) {
      warnAt(l.line, "link '" + l.name + "' is joined to '" + model.links.front().name +
                         "' by no joint; it moves with it as one rigid body");
    }
  }

  RigidTree tree;
  TreeBody body;
  body.link = model.links.empty() ? model.name : model.links.front().name;
  for (const LinkDescription& l : model.links) {
    body.merged_links.push_back(l.name);
    body.X_BL[l.name] = l.X_ML;
    tree.links[l.name] = {0, l.X_ML};
    // <inertial> in the link frame: COM at X_LI, inertia about it in I's axes.
    MassProperties m_L;
    m_L.mass = l.inertial.mass;
    m_L.com = l.inertial.X_LI.translation();
    m_L.inertia = l.inertial.X_LI.linear() * l.inertial.inertia * l.inertial.X_LI.linear().transpose();
    body.mass = combineMassProperties(body.mass, transformMassProperties(m_L, l.X_ML));
    for (const CollisionDescription& c : l.collisions) {
      CollisionGeometry g;
      g.link = l.name;
      g.X_BG = l.X_ML * c.X_LS;
      if (c.shape.type == ShapeType::kPlane) {
        warnAt(c.line, "collision '" + c.name +
                           "' is a plane, which cannot move: left out of the physics");
        continue;
      }
      g.shape = c.shape;
      body.collisions.push_back(g);
      surfaces->push_back(surfaceOf(c));
    }
  }
  if (body.collisions.empty()) {
    warnAt(model.line, "is dynamic but has no collision: nothing holds it up, it falls through "
                       "the ground (as in Gazebo)");
  }
  tree.bodies.push_back(std::move(body));
  return tree;
}

WorldModelBodies addModelToPhysics(const WorldDescription& world, const ModelDescription& model,
                                   PhysicsWorld* physics, const WarningSink& warn) {
  WorldModelBodies added;
  if (!model.is_static && !fixedToWorld(model) && !model.links.empty()) {
    std::vector<SurfaceParams> surfaces;
    RigidTree tree = freeBodyTree(world, model, &surfaces, warn);
    added.shapes = static_cast<int>(surfaces.size());
    try {
      added.free_body = physics->addFreeBody(std::move(tree), surfaces, model.X_WM, model.name);
    } catch (const PhysicsError& e) {
      throw PhysicsError(at(world, model.line) + e.what());
    }
    return added;
  }
  try {
    for (const LinkDescription& link : model.links) {
      for (const CollisionDescription& c : link.collisions) {
        StaticShape s;
        s.name = model.name + "::" + link.name + "::" + c.name;
        s.X_WS = model.X_WM * link.X_ML * c.X_LS;
        s.surface = surfaceOf(c);
        s.shape = c.shape;
        added.statics.push_back(physics->addStaticShape(s));
        ++added.shapes;
      }
    }
  } catch (...) {
    removeModelFromPhysics(added, physics);
    throw;
  }
  return added;
}

void removeModelFromPhysics(const WorldModelBodies& bodies, PhysicsWorld* physics) {
  if (bodies.free_body >= 0) physics->removeFreeBody(bodies.free_body);
  for (const int s : bodies.statics) physics->removeStaticShape(s);
}

int addWorldToPhysics(const WorldDescription& world, PhysicsWorld* physics,
                      const WarningSink& warn) {
  int added = 0;
  for (const ModelDescription& model : world.models) {
    added += addModelToPhysics(world, model, physics, warn).shapes;
  }
  return added;
}

void updateFreeBodyScene(const PhysicsWorld& physics, Scene* scene) {
  if (physics.freeBodyCount() == 0) return;
  for (SceneBody& body : scene->bodies) {
    if (body.is_static || body.name.size() <= body.model.size() + 2) continue;
    const int i = physics.freeBodyIndex(body.model);
    if (i < 0) continue;
    body.X_WB = physics.freeBody(i).linkPose(body.name.substr(body.model.size() + 2));
  }
}

}  // namespace tianracer_sim
