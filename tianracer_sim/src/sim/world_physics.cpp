#include "tianracer_sim/sim/world_physics.h"
#include "tianracer_sim/common/input_limits.h"

#include <algorithm>
#include <cmath>
#include <functional>
#include <map>
#include <sstream>
#include <string>

#include <Eigen/Eigenvalues>

#include "tianracer_sim/common/text.h"
#include "tianracer_sim/physics/mass_properties.h"

namespace tianracer_sim {

namespace {

std::string at(const WorldDescription& world, int line) {
  return world.source + ":" + std::to_string(line) + ": ";
}


bool movableType(const std::string& type) {
  return type == "revolute" || type == "continuous" || type == "prismatic";
}

/// SDF's "no limit": sdformat's joint.sdf defaults <lower>/<upper> to -+1e16.
constexpr double kNoLimit = 1e16;

/// How the links of a model hang together. Node n (one past the links) is the world.
struct LinkGraph {
  int world = 0;                  // the world's node index (= number of links)
  std::vector<int> parent;        // per link: parent node, or -1 (the root of a tree)
  std::vector<int> joint;         // per link: index into model.joints of the joint to its parent
  std::vector<bool> fixed;        // per link: that joint holds it fixed
  /// The root of node i's tree: a link index, or `world`.
  int root(int i) const {
    while (i != world && parent[i] >= 0) i = parent[i];
    return i;
  }
};

/// Joints read as a forest: a joint whose child already has a parent or that closes a loop
/// is left out (a btMultiBody is a tree), each with a warning through `warnAt`.
LinkGraph linkGraph(const ModelDescription& model,
                    const std::function<void(int, const std::string&)>& warnAt) {
  const int n = static_cast<int>(model.links.size());
  std::map<std::string, int> index;
  for (int i = 0; i < n; ++i) index[model.links[i].name] = i;
  index["world"] = n;
  LinkGraph g;
  g.world = n;
  g.parent.assign(n, -1);
  g.joint.assign(n, -1);
  g.fixed.assign(n, true);
  for (int k = 0; k < static_cast<int>(model.joints.size()); ++k) {
    const JointDescription& j = model.joints[k];
    const std::string what = "joint '" + j.name + "'";
    const bool movable = movableType(j.type);
    if (!movable && j.type != "fixed") {
      warnAt(j.line, what + " (" + j.type + ") is not simulated and is held fixed (simulated: "
                     "fixed, revolute, continuous, prismatic)");
    }
    const auto pi_it = index.find(j.parent), ci_it = index.find(j.child);
    if (pi_it == index.end() || ci_it == index.end()) continue;  // the parser reported it
    int p = pi_it->second, c = ci_it->second;
    if (c == n) {
      if (movable) {
        warnAt(j.line, what + " has the world as its child: left out (make the world its parent)");
        continue;
      }
      std::swap(p, c);  // a fixed joint holds either way
    }
    if (p == c) {
      warnAt(j.line, what + " joins link '" + j.child + "' to itself: left out");
      continue;
    }
    if (g.parent[c] >= 0) {
      warnAt(j.line, what + ": link '" + model.links[c].name + "' is already the child of joint '" +
                         model.joints[g.joint[c]].name +
                         "' and a link has one parent (closed chains are not simulated): left out");
      continue;
    }
    if (g.root(p) == c) {
      warnAt(j.line, what + " closes a loop of joints (closed chains are not simulated): left out");
      continue;
    }
    g.parent[c] = p;
    g.joint[c] = k;
    g.fixed[c] = !movable;
  }
  return g;
}

}  // namespace

PhysicsOptions physicsOptionsFor(const WorldDescription& world, PhysicsOptions base) {
  base.dt = world.physics.max_step_size;
  base.gravity = world.physics.gravity;
  base.ground_plane = world.ground_plane;
  base.ground_mu = world.ground_friction.mu;
  base.ground_mu2 = world.ground_friction.mu2;
  if (world.physics.friction_model == "cone_model") base.friction_model = FrictionModel::kCone;
  else if (world.physics.friction_model == "box_model") base.friction_model = FrictionModel::kBox;
  else base.friction_model = FrictionModel::kPyramid;
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
  s.collide_without_contact = c.contact.collide_without_contact;
  s.collide_without_contact_bitmask = c.contact.collide_without_contact_bitmask;
  s.collide_bitmask = c.contact.collide_bitmask;
  return s;
}

StaticShape staticShapeOf(const ModelDescription& model, const LinkDescription& link,
                          const CollisionDescription& c) {
  StaticShape s;
  s.name = model.name + "::" + link.name + "::" + c.name;
  s.X_WS = model.X_WM * link.X_ML * c.X_LS;
  s.surface = surfaceOf(c);
  s.shape = c.shape;
  return s;
}

bool isHeldStatic(const ModelDescription& model) {
  if (model.is_static || model.links.empty()) return true;
  // Gazebo: a model welded to the world (every link reaches it through fixed joints) never
  // moves.
  const LinkGraph g = linkGraph(model, [](int, const std::string&) {});
  for (int i = 0; i < static_cast<int>(model.links.size()); ++i) {
    for (int a = i; a != g.world; a = g.parent[a]) {
      if (a < 0 || !g.fixed[a]) return false;
    }
  }
  return true;
}

RigidTree worldModelTree(const WorldDescription& world, const ModelDescription& model,
                         std::vector<SurfaceParams>* surfaces, const WarningSink& warn) {
  const std::string what = "model '" + model.name + "'";
  auto warnAt = [&](int line, const std::string& message) {
    if (warn) warn(at(world, line) + what + ": " + message);
  };
  const int n = static_cast<int>(model.links.size());
  if (n == 0) throw PhysicsError(at(world, model.line) + what + " has no <link>");
  const LinkGraph g = linkGraph(model, warnAt);

  // Trees in order: the world's (a fixed base), the canonical (first) link's, then the others
  // by their root's place in the model. Bodies depth first, children in model order.
  std::vector<int> roots;
  bool has_world = false;
  for (int i = 0; i < n; ++i) has_world = has_world || g.root(i) == g.world;
  if (has_world) roots.push_back(g.world);
  if (g.root(0) != g.world) roots.push_back(g.root(0));
  for (int i = 0; i < n; ++i)
    if (g.parent[i] < 0 && std::find(roots.begin(), roots.end(), i) == roots.end()) roots.push_back(i);

  RigidTree tree;
  tree.fixed_base = has_world;
  std::vector<Eigen::Isometry3d> X_MB;  // per body: its frame in the model frame, joints at 0
  std::vector<std::vector<SurfaceParams>> body_surfaces;  // per body, per collision
  std::vector<int> body_of(n, -1);

  // Node i (a link, or the world) goes into body b; its fixed children join b, each movable
  // one starts a body of its own whose frame is the joint frame J.
  std::function<void(int, int)> visit = [&](int i, int b) {
    if (i < n) {
      const LinkDescription& l = model.links[i];
      body_of[i] = b;
      const Eigen::Isometry3d X_BL = X_MB[b].inverse() * l.X_ML;
      tree.bodies[b].merged_links.push_back(l.name);
      tree.bodies[b].self_collide = tree.bodies[b].self_collide || l.self_collide;
      tree.bodies[b].X_BL[l.name] = X_BL;
      tree.links[l.name] = {b, X_BL};
      if (!(has_world && b == 0)) {  // links welded to the world need no mass
        // <inertial> in the link frame: COM at X_LI, inertia about it in I's axes.
        MassProperties m_L;
        m_L.mass = l.inertial.mass;
        m_L.com = l.inertial.X_LI.translation();
        m_L.inertia =
            l.inertial.X_LI.linear() * l.inertial.inertia * l.inertial.X_LI.linear().transpose();
        tree.bodies[b].mass =
            combineMassProperties(tree.bodies[b].mass, transformMassProperties(m_L, X_BL));
        if (!l.gravity) {
          tree.bodies[b].gravity_free =
              combineMassProperties(tree.bodies[b].gravity_free, transformMassProperties(m_L, X_BL));
        }
      }
      for (const CollisionDescription& c : l.collisions) {
        if (c.shape.type == ShapeType::kPlane) {
          warnAt(c.line, "collision '" + c.name + "' is a plane, which cannot move: left out of the physics");
          continue;
        }
        CollisionGeometry geom;
        geom.link = l.name;
        geom.X_BG = X_BL * c.X_LS;
        geom.shape = c.shape;
        tree.bodies[b].collisions.push_back(geom);
        body_surfaces[b].push_back(surfaceOf(c));
      }
    }
    for (int k = 0; k < n; ++k) {
      if (g.parent[k] != i) continue;
      if (g.fixed[k]) {
        visit(k, b);
        continue;
      }
      const JointDescription& j = model.joints[g.joint[k]];
      TreeBody child;
      child.link = model.links[k].name;
      child.parent = b;
      child.joint = j.name;
      const Eigen::Isometry3d X_MJ = model.links[k].X_ML * j.X_CJ;
      child.X_PB = X_MB[b].inverse() * X_MJ;
      child.axis_B = j.axis;
      child.joint_type = j.type == "prismatic"    ? TreeJointType::kPrismatic
                         : j.type == "continuous" ? TreeJointType::kContinuous
                                                  : TreeJointType::kRevolute;
      if (child.joint_type != TreeJointType::kContinuous &&
          (j.lower > -kNoLimit || j.upper < kNoLimit)) {
        if (j.lower <= j.upper) {
          child.has_position_limits = true;
          child.lower = std::max(j.lower, -kNoLimit);
          child.upper = std::min(j.upper, kNoLimit);
        } else {
          warnAt(j.line, "joint '" + j.name + "': <limit> <lower> " + formatShort(j.lower) +
                             " is above <upper> " + formatShort(j.upper) + ": the joint has no limits");
        }
      }
      child.effort_limit = j.effort > 0.0 ? j.effort : 0.0;
      child.velocity_limit = j.velocity > 0.0 ? j.velocity : 0.0;
      child.damping = j.damping;
      child.friction = j.friction;
      child.spring_stiffness = j.spring_stiffness;
      child.spring_reference = j.spring_reference;
      tree.bodies.push_back(child);
      X_MB.push_back(X_MJ);
      body_surfaces.emplace_back();
      visit(k, static_cast<int>(tree.bodies.size()) - 1);
    }
  };
  for (const int r : roots) {
    TreeBody root;
    root.link = r == g.world ? "world" : model.links[r].name;
    tree.bodies.push_back(root);
    X_MB.push_back(Eigen::Isometry3d::Identity());  // every root's frame is the model frame
    body_surfaces.emplace_back();
    visit(r, static_cast<int>(tree.bodies.size()) - 1);
  }

  // Gazebo filters each pair of collisions (ODEPhysics::Collide); Bullet filters and answers
  // per collision object, here a body (links joined by fixed joints): its masks are the union
  // of its collisions', and it collides without contact only when all of them do.
  for (std::size_t b = 0; b < body_surfaces.size(); ++b) {
    const std::vector<SurfaceParams>& bs = body_surfaces[b];
    if (bs.size() < 2) continue;
    bool any_without = false, all_without = true, masks_differ = false;
    for (const SurfaceParams& s : bs) {
      any_without = any_without || s.collide_without_contact;
      all_without = all_without && s.collide_without_contact;
      masks_differ = masks_differ || s.collide_bitmask != bs[0].collide_bitmask ||
                     s.collide_without_contact_bitmask != bs[0].collide_without_contact_bitmask;
    }
    const std::string link = "link '" + tree.bodies[b].link + "'";
    if (any_without && !all_without) {
      warnAt(model.line, link + ": <collide_without_contact> on some of the collisions that move "
                         "with it, not all: they push as the others do (Bullet answers contacts "
                         "per body)");
    }
    if (masks_differ) {
      warnAt(model.line, link + ": its collisions (with the links fixed to it) have different "
                         "collide bitmasks: each collides as their union (OR)");
    }
  }
  for (const auto& bs : body_surfaces) surfaces->insert(surfaces->end(), bs.begin(), bs.end());
  if (surfaces->empty()) {
    warnAt(model.line, "is dynamic but has no collision: nothing holds it up, it falls through "
                       "the ground (as in Gazebo)");
  }

  // The model frame moves with the canonical (first) link.
  tree.canonical_body = body_of[0];
  if (tree.bodies[tree.canonical_body].parent >= 0) tree.X_BM = X_MB[tree.canonical_body].inverse();

  // Every moving link needs a mass and an inertia (ODE refuses a massless body: ODELink.cc's
  // UpdateMass); a body of several links needs a physical sum.
  for (std::size_t b = 0; b < tree.bodies.size(); ++b) {
    const TreeBody& body = tree.bodies[b];
    if (has_world && b == 0) continue;
    for (const std::string& name : body.merged_links) {
      const LinkDescription& l =
          *std::find_if(model.links.begin(), model.links.end(),
                        [&](const LinkDescription& d) { return d.name == name; });
      const int line = l.inertial.line > 0 ? l.inertial.line : l.line;
      const std::string lwhat = at(world, line) + what + " link '" + l.name + "': ";
      if (!(l.inertial.mass > 0.0) || !std::isfinite(l.inertial.mass)) {
        throw PhysicsError(lwhat + "<mass> must be > 0 (got " + formatShort(l.inertial.mass) +
                           ") for a link that moves");
      }
      if (l.inertial.mass > limits::kMass) {
        throw PhysicsError(lwhat + "<mass> " + formatShort(l.inertial.mass) + " is out of range (<= " +
                           limits::formatNumber(limits::kMass) + " kg) for a link that moves");
      }
      const Eigen::Matrix3d& I = l.inertial.inertia;
      if (I.allFinite() && I.cwiseAbs().maxCoeff() > limits::kInertia) {
        throw PhysicsError(lwhat + "inertia component " + formatShort(I.cwiseAbs().maxCoeff()) +
                           " is out of range (<= " + limits::formatNumber(limits::kInertia) +
                           " kg m^2) for a link that moves");
      }
      const Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> eig(I);
      if (!I.allFinite() || !(eig.eigenvalues().minCoeff() > 0.0)) {
        std::ostringstream os;
        os << lwhat << "inertia (ixx iyy izz ixy ixz iyz) = (" << I(0, 0) << " " << I(1, 1) << " "
           << I(2, 2) << " " << I(0, 1) << " " << I(0, 2) << " " << I(1, 2)
           << ") is not positive definite; a link that moves needs a positive inertia";
        throw PhysicsError(os.str());
      }
    }
    if (!isPhysicalInertia(body.mass.inertia)) {
      // No rigid body has such moments, but ODE checks only that the inertia is positive
      // definite (dMassCheck), so Gazebo simulates it as given (the library's create base:
      // izz 1.53 over ixx, iyy 0.059). So do we, with a warning.
      const Eigen::Vector3d I = principalInertia(body.mass.inertia).moments;
      std::ostringstream os;
      os << at(world, model.line) << what << " link '" << body.link
         << "': the principal moments of inertia of the links moving with it, (" << I.x() << " "
         << I.y() << " " << I.z() << "), violate the triangle inequality (each at most the sum "
         << "of the other two); simulated as given, as Gazebo does";
      if (warn) warn(os.str());
    }
  }
  return tree;
}

WorldModelBodies addModelToPhysics(const WorldDescription& world, const ModelDescription& model,
                                   PhysicsWorld* physics, const WarningSink& warn) {
  WorldModelBodies added;
  if (!isHeldStatic(model)) {
    std::vector<SurfaceParams> surfaces;
    RigidTree tree;
    bool movable = true;
    try {
      tree = worldModelTree(world, model, &surfaces, warn);
    } catch (const PhysicsError& e) {
      // Bad mass properties: the model stays where the file puts it; the rest of the world
      // loads.
      if (warn) warn(std::string(e.what()) + "; the model is held static");
      movable = false;
    }
    if (movable) {
      added.shapes = static_cast<int>(surfaces.size());
      try {
        added.free_body = physics->addFreeBody(std::move(tree), surfaces, model.X_WM, model.name);
        // Gazebo auto-disables the links of a resting model without joints (ODELink.cc, Init;
        // SDF <allow_auto_disable>, default true). A model with sensors must not sleep
        // either: whoever gives world models sensors calls allowSleep(false).
        physics->freeBody(added.free_body)
            .allowSleep(model.allow_auto_disable && model.joints.empty());
      } catch (const PhysicsError& e) {
        throw PhysicsError(at(world, model.line) + e.what());
      }
      return added;
    }
  }
  try {
    for (const LinkDescription& link : model.links) {
      for (const CollisionDescription& c : link.collisions) {
        added.statics.push_back(physics->addStaticShape(staticShapeOf(model, link, c)));
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
