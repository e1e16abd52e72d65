// What gazebo_ros's property services read and change (gazebo_ros/src/gazebo_ros_api_plugin.cpp:
// get/set_physics_properties, get/set_joint_properties, set_model_configuration,
// get_link_properties, get/set_light_properties, delete_light), as state changes of the
// Simulator without ROS (simulator/properties.h). Every setter checks all of its input before it
// changes anything.
#include "tianracer_sim/simulator/properties.h"

#include <cmath>
#include <sstream>

#include "tianracer_sim/sim/world_physics.h"
#include "tianracer_sim/simulator/simulator.h"

namespace tianracer_sim {

namespace {

std::string num(double v) {
  std::ostringstream os;
  os << v;
  return os.str();
}

bool finiteNonNegative(const Eigen::Vector4f& c) {
  return c.allFinite() && (c.array() >= 0.0f).all();
}

std::string colour(const Eigen::Vector4f& c) {
  std::ostringstream os;
  os << "(" << c[0] << ", " << c[1] << ", " << c[2] << ", " << c[3] << ")";
  return os.str();
}

}  // namespace

double worldTimeStep(const WorldDescription& world) { return physicsOptionsFor(world).dt; }

Properties::Properties(Simulator& sim, Simulation& simulation, Scene& scene,
                       std::function<void()> scene_moved, double max_update_rate)
    : sim_(sim),
      simulation_(simulation),
      scene_(scene),
      scene_moved_(std::move(scene_moved)),
      max_update_rate_(max_update_rate) {}

// --- physics ----------------------------------------------------------------------------------

PhysicsProperties Properties::physicsProperties() const {
  const PhysicsWorld& w = simulation_.physics();
  PhysicsProperties p;
  p.time_step = w.dt();
  p.max_update_rate = max_update_rate_;
  p.gravity = w.options().gravity;
  p.solver = w.solverSettings();
  p.solver_iterations = p.solver.iterations;
  p.contact_max_correcting_vel = w.options().contact_max_correcting_vel;
  p.auto_disable_bodies = w.options().sleep_time > 0.0;
  return p;
}

void Properties::setPhysicsProperties(const PhysicsProperties& p) {
  const PhysicsProperties now = physicsProperties();
  if (!(p.time_step > 0.0 && p.time_step <= kMaxTimeStep)) {
    throw InputError("physics: time_step must be in (0, " + num(kMaxTimeStep) + "] s, got " +
                     num(p.time_step));
  }
  if (!(p.max_update_rate >= 0.0) || !std::isfinite(p.max_update_rate)) {
    throw InputError("physics: max_update_rate must be finite and >= 0 (0 = as fast as possible), got " +
                     num(p.max_update_rate));
  }
  if (!p.gravity.allFinite() || p.gravity.cwiseAbs().maxCoeff() > kMaxGravity) {
    throw InputError("physics: gravity (" + num(p.gravity.x()) + ", " + num(p.gravity.y()) + ", " +
                     num(p.gravity.z()) + ") must be finite, each component within " +
                     num(kMaxGravity) + " m/s^2");
  }
  if (p.solver_iterations < 1 || p.solver_iterations > kMaxSolverIterations) {
    throw InputError("physics: sor_pgs_iters (solver iterations) must be in [1, " +
                     std::to_string(kMaxSolverIterations) + "], got " +
                     std::to_string(p.solver_iterations));
  }
  if (!(p.contact_max_correcting_vel > 0.0) || !std::isfinite(p.contact_max_correcting_vel)) {
    throw InputError("physics: contact_max_correcting_vel must be finite and > 0, got " +
                     num(p.contact_max_correcting_vel));
  }
  if (p.auto_disable_bodies != now.auto_disable_bodies) {
    throw InputError(std::string("physics: auto_disable_bodies cannot be changed here (it is ") +
                     (now.auto_disable_bodies ? "true" : "false") +
                     ": each world model's <allow_auto_disable> decides)");
  }
  sim_.waitFrames();  // the frame in flight was drawn with the old state
  simulation_.setTimeStep(p.time_step);
  simulation_.physics().setGravity(p.gravity);
  simulation_.physics().setSolverIterations(p.solver_iterations);
  simulation_.physics().setContactMaxCorrectingVel(p.contact_max_correcting_vel);
  max_update_rate_ = p.max_update_rate;
}

// --- joints -----------------------------------------------------------------------------------

JointProperties Properties::jointProperties(const std::string& name) const {
  const JointRef ref = sim_.entities().joint(name);
  const PhysicsRobot& p = *ref.body;
  const int i = ref.index;
  JointProperties j;
  j.model = p.name();
  j.info = p.joints()[i];
  j.position = p.jointPosition(i);
  j.rate = p.jointVelocity(i);
  return j;
}

void Properties::setJointProperties(const std::string& name, const JointPropertiesChange& c) {
  const JointRef ref = sim_.entities().joint(name);
  PhysicsRobot& p = *ref.body;
  const int i = ref.index;
  const JointInfo& j = p.joints()[i];
  const std::string what = "joint '" + name + "'";
  auto check = [&](const std::optional<double>& v, const char* field, bool non_negative) {
    if (v && (!std::isfinite(*v) || (non_negative && *v < 0.0))) {
      throw InputError(what + ": " + field + " must be finite" + (non_negative ? " and >= 0" : "") +
                       ", got " + num(*v));
    }
  };
  check(c.damping, "damping", true);
  check(c.friction, "friction", true);
  check(c.lower, "loStop", false);
  check(c.upper, "hiStop", false);
  check(c.velocity, "vel", false);
  check(c.fmax, "fmax", true);
  if (c.velocity.has_value() != c.fmax.has_value()) {
    throw InputError(what + ": vel and fmax go together (a velocity target needs its force cap)");
  }
  if (c.lower || c.upper) {
    if (j.type == JointType::kContinuous) {
      throw InputError(what + " is continuous: it has no position limits (loStop, hiStop)");
    }
    const double lo = c.lower.value_or(j.has_position_limits ? j.lower : -1e16);
    const double hi = c.upper.value_or(j.has_position_limits ? j.upper : 1e16);
    if (!(lo <= hi)) {
      throw InputError(what + ": loStop " + num(lo) + " is above hiStop " + num(hi));
    }
  }
  if (c.damping) p.setJointDamping(i, *c.damping);
  if (c.friction) p.setJointFriction(i, *c.friction);
  if (c.lower || c.upper) {
    p.setJointLimits(i, c.lower.value_or(j.has_position_limits ? j.lower : -1e16),
                     c.upper.value_or(j.has_position_limits ? j.upper : 1e16));
  }
  if (c.velocity) p.setJointVelocityTarget(i, *c.velocity, *c.fmax);
}

void Properties::setModelConfiguration(const std::string& model,
                                      const std::vector<std::string>& joints,
                                      const std::vector<double>& positions) {
  const ModelId id = sim_.findModel(model);
  if (id == kNoModel) throw InputError("set_model_configuration: no model named '" + model + "'");
  PhysicsRobot* p = sim_.physicsOf(id);
  if (!p) throw InputError("set_model_configuration: model '" + model + "' is static: its joints do not move");
  if (joints.size() != positions.size()) {
    throw InputError("set_model_configuration: model '" + model + "': " +
                     std::to_string(joints.size()) + " joint names but " +
                     std::to_string(positions.size()) + " positions");
  }
  std::vector<int> index(joints.size());
  for (std::size_t k = 0; k < joints.size(); ++k) {
    index[k] = p->jointIndex(joints[k]);
    if (index[k] < 0) {
      throw InputError("set_model_configuration: model '" + model + "' has no movable joint '" +
                       joints[k] + "'");
    }
    if (!std::isfinite(positions[k])) {
      throw InputError("set_model_configuration: model '" + model + "' joint '" + joints[k] +
                       "': position " + num(positions[k]) + " is not finite");
    }
  }
  for (std::size_t k = 0; k < joints.size(); ++k) p->setJointState(index[k], positions[k], 0.0);
  scene_moved_();  // links moved between steps
}

// --- links ------------------------------------------------------------------------------------

LinkProperties Properties::linkProperties(const std::string& name) const {
  Entity e;
  try {
    e = sim_.entities().find(name, false);
  } catch (const InputError& err) {
    throw InputError("link '" + name + "': " + err.what());
  }
  LinkProperties lp;
  if (e.robot) {
    for (const TreeBody& b : e.body->tree().bodies) {
      if (b.link == e.link) {
        lp.mass = b.mass.mass;  // body frame B = the link's frame; lumped children included
        lp.com = b.mass.com;
        lp.inertia = b.mass.inertia;
        return lp;
      }
      for (const std::string& merged : b.merged_links) {
        if (merged == e.link) {
          throw InputError("link '" + name + "' is joined to '" + b.link +
                           "' by fixed joints and lumped into it (as Gazebo's URDF import does): ask for '" +
                           e.model_name + "::" + b.link + "'");
        }
      }
    }
  } else if (e.model) {
    for (const LinkDescription& l : e.model->links) {
      if (l.name != e.link) continue;
      lp.mass = l.inertial.mass;
      lp.com = l.inertial.X_LI.translation();
      lp.inertia = l.inertial.inertia;
      return lp;
    }
  } else if (e.ground_plane) {
    throw InputError("link '" + name + "': the ground plane is static and has no inertial");
  }
  throw InputError("link '" + name + "': model '" + e.model_name + "' has no link '" + e.link + "'");
}

// --- lights -----------------------------------------------------------------------------------

void Properties::setLight(const std::string& name, const LightChange& c) {
  DirectionalLight* light = nullptr;
  std::string known;
  for (DirectionalLight& l : scene_.lights) {
    if (l.name == name) light = &l;
    known += (known.empty() ? "" : ", ") + l.name;
  }
  if (!light) throw InputError("light '" + name + "' not found (lights: " + (known.empty() ? "none" : known) + ")");
  const std::string what = "light '" + name + "'";
  if (!finiteNonNegative(c.diffuse)) throw InputError(what + ": diffuse " + colour(c.diffuse) + " must be finite and >= 0");
  if (!finiteNonNegative(c.specular)) throw InputError(what + ": specular " + colour(c.specular) + " must be finite and >= 0");
  const Attenuation& a = c.attenuation;
  for (double v : {a.constant, a.linear, a.quadratic}) {
    if (!(v >= 0.0) || !std::isfinite(v)) {
      throw InputError(what + ": attenuation (" + num(a.constant) + ", " + num(a.linear) + ", " +
                       num(a.quadratic) + ") must be finite and >= 0");
    }
  }
  if (!c.direction.allFinite()) throw InputError(what + ": direction is not finite");
  light->given_diffuse = c.diffuse;
  light->given_specular = c.specular;
  light->attenuation = a;
  if (c.direction.norm() > 0.0) light->direction = c.direction.normalized();
  litColours(light);
}

void Properties::deleteLight(const std::string& name) {
  for (auto it = scene_.lights.begin(); it != scene_.lights.end(); ++it) {
    if (it->name == name) {
      scene_.lights.erase(it);
      return;
    }
  }
  throw InputError("light '" + name + "' not found");
}

}  // namespace tianracer_sim
