// The robot API (PhysicsRobot) and how its commands reach Bullet each step.
#include <algorithm>
#include <cassert>
#include <cmath>

#include "world_impl.h"

namespace tianracer_sim {

btTransform RobotState::comFrame(int b) const {
  btMultiBody* mb = mbOfBody(b);
  const int link = body_link[b];
  if (link < 0) return mb->getBaseWorldTransform();
  mb->forwardKinematics(scratch_q, scratch_p);
  const btQuaternion& q = scratch_q[link + 1];
  return btTransform(q.inverse(), scratch_p[link + 1]);
}

Eigen::Isometry3d RobotState::bodyPose(int b) const {
  return toEigen(comFrame(b)) * X_BC[b].inverse();
}

Twist RobotState::bodyTwistAt(int b, const Eigen::Vector3d& p_W) const {
  // Bullet gives each body's COM velocity and angular velocity in the body's COM frame.
  btMultiBody* mb = mbOfBody(b);
  mb->compTreeLinkVelocities(&scratch_w[0], &scratch_v[0]);
  const int k = body_link[b] + 1;
  const btTransform X_WC = comFrame(b);
  Twist t;
  t.angular = toEigen(X_WC.getBasis() * scratch_w[k]);
  const Eigen::Vector3d v_com = toEigen(X_WC.getBasis() * scratch_v[k]);
  t.linear = v_com + t.angular.cross(p_W - toEigen(X_WC.getOrigin()));
  return t;
}

void RobotState::wake() {
  if (!world_model) return;  // robots never sleep
  for (const Part& part : parts) {
    if (!part.mb->getCanSleep()) continue;
    if (multiBodyAsleep(*part.mb)) {
      // Bullet adds gravity at the start of a step and clears forces at its end only for
      // bodies awake then: one that fell asleep within the step keeps that step's gravity,
      // which the next step's would double. (Woken by a contact instead, Bullet skips that
      // step's gravity and uses the kept one.)
      part.mb->clearForcesAndTorques();
    }
    part.mb->wakeUp();
  }
  for (auto& c : colliders) {
    // activate() leaves DISABLE_DEACTIVATION (never sleeps) alone.
    if (c && !c->isStaticObject()) c->activate(true);
  }
}

void RobotState::syncColliders() {
  for (const Part& part : parts) {
    part.mb->forwardKinematics(scratch_q, scratch_p);
    part.mb->updateCollisionObjectWorldTransforms(scratch_q, scratch_p);
  }
  for (auto& c : colliders) {
    if (c) world->world->updateSingleAabb(c.get());
  }
}

/// Links that feel no gravity (TreeBody::gravity_free): Bullet gives every body m g at its COM,
/// so -m_free g is added at the gravity-free links' COM, a force and its moment about the body's
/// COM. Bullet applies gravity only to a multibody that is not asleep (and clears forces only of
/// those; multiBodyAsleep), so a sleeping one gets nothing here either.
void PhysicsWorld::Impl::applyGravityFree(RobotState* r) {
  if (!r->has_gravity_free) return;
  const btVector3 g = toBt(options.gravity);
  for (std::size_t b = 0; b < r->tree.bodies.size(); ++b) {
    const MassProperties& free = r->tree.bodies[b].gravity_free;
    if (!(free.mass > 0.0)) continue;
    btMultiBody* mb = r->mbOfBody(static_cast<int>(b));
    if (multiBodyAsleep(*mb)) continue;
    const btTransform X_WC = r->comFrame(static_cast<int>(b));
    // The free mass's COM in C (precomputed), then in the world.
    const btVector3 arm = X_WC.getBasis() * toBt(r->gravity_free_com_C[b]);
    const btVector3 f = -free.mass * g;
    const int link = r->body_link[b];
    if (link < 0) {
      mb->addBaseForce(f);
      mb->addBaseTorque(arm.cross(f));
    } else {
      mb->addLinkForce(link, f);
      mb->addLinkTorque(link, arm.cross(f));
    }
  }
}

void PhysicsWorld::Impl::applyCommands(RobotState* r) {
  const double dt = options.dt;
  // A limit constraint costs two solver rows every step, also far from the limit: it joins the
  // solve only while the joint is within 0.05 rad (or two steps of travel) of either end, so it
  // cannot be crossed unseen.
  for (std::size_t k = 0; k < r->limits.size(); ++k) {
    const JointInfo& j = r->joints[k];
    btMultiBody* mb = r->mbOfJoint(static_cast<int>(k));
    const int link = r->linkOfJoint(static_cast<int>(k));
    bool near = false;
    if (j.has_position_limits) {
      const double q = mb->getJointPos(link);
      const double margin = 0.05 + 2.0 * std::abs(mb->getJointVel(link)) * dt;
      near = q - j.lower < margin || j.upper - q < margin;
    }
    if (near != r->limit_in_world[k]) {
      if (near) {
        if (!r->limits[k]) {
          auto lim = std::make_unique<btMultiBodyJointLimitConstraint>(mb, link, j.lower, j.upper);
          lim->finalizeMultiDof();
          r->limits[k] = std::move(lim);
        }
        world->addMultiBodyConstraint(r->limits[k].get());
      } else {
        world->removeMultiBodyConstraint(r->limits[k].get());
      }
      r->limit_in_world[k] = near;
    }
  }
  if (r->has_ext_wrench) {
    // A body asleep would keep the force unapplied (Bullet clears no forces of a sleeping
    // multibody): a wrench keeps it awake.
    if (r->world_model) r->wake();
    for (std::size_t b = 0; b < r->ext_force.size(); ++b) {
      const btVector3 f = toBt(r->ext_force[b]), t = toBt(r->ext_torque[b]);
      btMultiBody* mb = r->mbOfBody(static_cast<int>(b));
      const int link = r->body_link[b];
      if (link < 0) {
        mb->addBaseForce(f);
        mb->addBaseTorque(t);
      } else {
        mb->addLinkForce(link, f);
        mb->addLinkTorque(link, t);
      }
    }
  }
  applyGravityFree(r);
  for (std::size_t i = 0; i < r->joints.size(); ++i) {
    const JointInfo& j = r->joints[i];
    const RobotState::Command& c = r->commands[i];
    btMultiBody* mb = r->mbOfJoint(static_cast<int>(i));
    const int link = r->linkOfJoint(static_cast<int>(i));
    double tau = (c.mode == RobotState::Mode::kEffort ? c.effort : 0.0) + r->ext_effort[i];
    if (j.spring_stiffness != 0.0) tau -= j.spring_stiffness * (mb->getJointPos(link) - j.spring_reference);
    if (tau != 0.0) mb->addJointTorque(link, tau);

    // Viscous damping in the solve, implicitly (JointDamper): stable for any damping.
    const bool damped = j.damping > 0.0;
    if (damped && !r->dampers[i]) {
      r->dampers[i] = std::make_unique<JointDamper>(mb, link);
      r->dampers[i]->finalizeMultiDof();
    }
    if (damped) r->dampers[i]->setDamping(j.damping);
    if (damped != r->damper_in_world[i]) {
      if (damped) world->addMultiBodyConstraint(r->dampers[i].get());
      else world->removeMultiBodyConstraint(r->dampers[i].get());
      r->damper_in_world[i] = damped;
    }

    double target = 0.0, max_impulse = 0.0;
    if (c.mode == RobotState::Mode::kVelocity) {
      target = c.velocity;
      max_impulse = c.max_effort * dt;
    } else if (j.friction > 0.0) {
      max_impulse = j.friction * dt;
    }
    if (max_impulse > 0.0 && !r->motor_in_world[i]) {
      if (!r->motors[i]) {
        r->motors[i] = std::make_unique<btMultiBodyJointMotor>(mb, link, 0.0, 0.0);
        r->motors[i]->finalizeMultiDof();  // allocates the row data read by jointEffort()
      }
      world->addMultiBodyConstraint(r->motors[i].get());
      r->motor_in_world[i] = true;
    }
    btMultiBodyJointMotor* motor = r->motors[i].get();
    if (r->motor_in_world[i]) {
      motor->setVelocityTarget(target, 1.0);
      motor->setMaxAppliedImpulse(max_impulse);
    }
  }
}

// ---------------------------------------------------------------------------------------------
// PhysicsRobot

const std::string& PhysicsRobot::name() const { return s_->name; }
const RigidTree& PhysicsRobot::tree() const { return s_->tree; }
const std::vector<JointInfo>& PhysicsRobot::joints() const { return s_->joints; }

int PhysicsRobot::jointIndex(const std::string& joint_name) const {
  auto it = s_->joint_index.find(joint_name);
  return it == s_->joint_index.end() ? -1 : it->second;
}

namespace {
void checkJoint(const RobotState* s, int i) {
  if (i < 0 || i >= static_cast<int>(s->joints.size())) {
    throw PhysicsError("robot '" + s->name + "': no joint index " + std::to_string(i));
  }
}
}  // namespace

double PhysicsRobot::jointPosition(int i) const {
  checkJoint(s_, i);
  return s_->mbOfJoint(i)->getJointPos(s_->linkOfJoint(i));
}
double PhysicsRobot::jointVelocity(int i) const {
  checkJoint(s_, i);
  return s_->mbOfJoint(i)->getJointVel(s_->linkOfJoint(i));
}
double PhysicsRobot::jointEffort(int i) const {
  checkJoint(s_, i);
  return s_->applied_effort[i];
}

void PhysicsRobot::setJointEffort(int i, double tau) {
  checkJoint(s_, i);
  assert(std::isfinite(tau) && "setJointEffort: non-finite effort");
  if (!std::isfinite(tau)) {
    ++s_->rejected;
    return;
  }
  const double lim = s_->joints[i].effort_limit;
  if (lim > 0.0) tau = std::max(-lim, std::min(lim, tau));
  auto& c = s_->commands[i];
  c.mode = RobotState::Mode::kEffort;
  c.effort = tau;
  s_->wake();
}

void PhysicsRobot::setJointVelocityTarget(int i, double omega, double max_effort) {
  checkJoint(s_, i);
  assert(std::isfinite(omega) && std::isfinite(max_effort) &&
         "setJointVelocityTarget: non-finite command");
  if (!std::isfinite(omega) || !std::isfinite(max_effort)) {
    ++s_->rejected;
    return;
  }
  auto& c = s_->commands[i];
  c.mode = RobotState::Mode::kVelocity;
  c.velocity = omega;
  c.max_effort = max_effort < 0.0 ? s_->joints[i].motor_effort : max_effort;
  s_->wake();
}

void PhysicsRobot::clearJointCommand(int i) {
  checkJoint(s_, i);
  s_->commands[i] = RobotState::Command();
}

void PhysicsRobot::setJointState(int i, double position, double velocity) {
  checkJoint(s_, i);
  if (!std::isfinite(position) || !std::isfinite(velocity)) {
    ++s_->rejected;
    return;
  }
  s_->mbOfJoint(i)->setJointPos(s_->linkOfJoint(i), position);
  s_->mbOfJoint(i)->setJointVel(s_->linkOfJoint(i), velocity);
  s_->syncColliders();
  s_->wake();
}

namespace {
std::string jointWhat(const RobotState* s, int i) {
  return (s->world_model ? "model '" : "robot '") + s->name + "' joint '" + s->joints[i].name + "'";
}
}  // namespace

void PhysicsRobot::setJointDamping(int i, double damping) {
  checkJoint(s_, i);
  if (!(damping >= 0.0) || !std::isfinite(damping)) {
    throw PhysicsError(jointWhat(s_, i) + ": damping must be finite and >= 0, got " +
                       std::to_string(damping));
  }
  s_->joints[i].damping = damping;
  s_->wake();
}

void PhysicsRobot::setJointFriction(int i, double friction) {
  checkJoint(s_, i);
  if (!(friction >= 0.0) || !std::isfinite(friction)) {
    throw PhysicsError(jointWhat(s_, i) + ": friction must be finite and >= 0, got " +
                       std::to_string(friction));
  }
  s_->joints[i].friction = friction;
  s_->wake();
}

void PhysicsRobot::setJointLimits(int i, double lower, double upper) {
  checkJoint(s_, i);
  JointInfo& j = s_->joints[i];
  if (j.type == JointType::kContinuous) {
    throw PhysicsError(jointWhat(s_, i) + " is continuous: it has no position limits");
  }
  if (!std::isfinite(lower) || !std::isfinite(upper) || !(lower <= upper)) {
    throw PhysicsError(jointWhat(s_, i) + ": limits must be finite with lower <= upper, got " +
                       std::to_string(lower) + " .. " + std::to_string(upper));
  }
  j.has_position_limits = true;
  j.lower = lower;
  j.upper = upper;
  if (s_->limits[i]) {
    s_->limits[i]->setLowerBound(lower);
    s_->limits[i]->setUpperBound(upper);
  }
  s_->wake();
}

void PhysicsRobot::setJointExternalEffort(int i, double effort) {
  checkJoint(s_, i);
  if (!std::isfinite(effort)) {
    ++s_->rejected;
    return;
  }
  if (effort != s_->ext_effort[i]) s_->wake();
  s_->ext_effort[i] = effort;
}

double PhysicsRobot::jointExternalEffort(int i) const {
  checkJoint(s_, i);
  return s_->ext_effort[i];
}

std::uint64_t PhysicsRobot::rejectedCommands() const { return s_->rejected; }

// The model frame M: X_WM = X_WB X_BM with B the canonical body's frame (robots: body 0, X_BM
// identity, computed exactly as X_WC X_BC^-1 of the base).
Eigen::Isometry3d PhysicsRobot::basePose() const {
  const RigidTree& tree = s_->tree;
  if (tree.canonical_body == 0 && s_->singleTree()) {
    return toEigen(s_->parts[0].mb->getBaseWorldTransform()) * s_->X_BC[0].inverse();
  }
  return s_->bodyPose(tree.canonical_body) * tree.X_BM;
}

Twist PhysicsRobot::baseTwist() const {
  const RigidTree& tree = s_->tree;
  if (tree.canonical_body == 0 && s_->singleTree()) {
    const btMultiBody* mb = s_->parts[0].mb.get();
    Twist t;
    t.angular = toEigen(mb->getBaseOmega());
    const Eigen::Vector3d v_com = toEigen(mb->getBaseVel());
    const btTransform X_WC = mb->getBaseWorldTransform();
    const Eigen::Vector3d p_com = toEigen(X_WC.getOrigin());
    const Eigen::Vector3d p_origin = basePose().translation();
    t.linear = v_com + t.angular.cross(p_origin - p_com);
    return t;
  }
  return s_->bodyTwistAt(tree.canonical_body, basePose().translation());
}

void PhysicsRobot::setBasePose(const Eigen::Isometry3d& X_WB) {
  if (!X_WB.matrix().allFinite()) {
    ++s_->rejected;
    return;
  }
  Eigen::Isometry3d X = X_WB;
  X.linear() = Eigen::Quaterniond(X_WB.rotation()).normalized().toRotationMatrix();
  if (s_->tree.canonical_body == 0 && s_->singleTree()) {
    s_->parts[0].mb->setBaseWorldTransform(toBt(Eigen::Isometry3d(X * s_->X_BC[0])));
  } else {
    // Every tree moves with the model frame, keeping its pose relative to it (Gazebo's
    // Model::SetWorldPose moves each link so).
    const Eigen::Isometry3d X_MW = basePose().inverse();
    for (const RobotState::Part& part : s_->parts) {
      const Eigen::Isometry3d X_WC = toEigen(part.mb->getBaseWorldTransform());
      part.mb->setBaseWorldTransform(toBt(Eigen::Isometry3d(X * (X_MW * X_WC))));
    }
  }
  s_->syncColliders();
  s_->wake();
}

void PhysicsRobot::setBaseTwist(const Twist& twist) {
  if (!twist.linear.allFinite() || !twist.angular.allFinite()) {
    ++s_->rejected;
    return;
  }
  // The rigid velocity field of the model frame at each tree's base COM (joint rates kept).
  const Eigen::Vector3d p_origin = basePose().translation();
  for (const RobotState::Part& part : s_->parts) {
    if (part.mb->hasFixedBase()) continue;
    const Eigen::Vector3d p_com = toEigen(part.mb->getBaseWorldTransform().getOrigin());
    part.mb->setBaseVel(toBt(Eigen::Vector3d(twist.linear + twist.angular.cross(p_com - p_origin))));
    part.mb->setBaseOmega(toBt(twist.angular));
  }
  s_->wake();
}

void PhysicsRobot::setModelTwist(const Twist& twist) {
  if (!twist.linear.allFinite() || !twist.angular.allFinite()) {
    ++s_->rejected;
    return;
  }
  for (std::size_t i = 0; i < s_->joints.size(); ++i)
    s_->mbOfJoint(static_cast<int>(i))->setJointVel(s_->linkOfJoint(static_cast<int>(i)), 0.0);
  setBaseTwist(twist);
}

void PhysicsRobot::resetToSpawn() {
  for (std::size_t i = 0; i < s_->joints.size(); ++i) {
    btMultiBody* mb = s_->mbOfJoint(static_cast<int>(i));
    mb->setJointPos(s_->linkOfJoint(static_cast<int>(i)), 0.0);
    mb->setJointVel(s_->linkOfJoint(static_cast<int>(i)), 0.0);
    s_->commands[i] = RobotState::Command();
    s_->applied_effort[i] = 0.0;
    s_->ext_effort[i] = 0.0;
  }
  // Every tree's root frame is the spawn frame at spawn (rigid_tree.h).
  for (const RobotState::Part& part : s_->parts) {
    part.mb->setBaseWorldTransform(toBt(Eigen::Isometry3d(s_->spawn * s_->X_BC[part.root])));
    part.mb->setBaseVel(btVector3(0, 0, 0));
    part.mb->setBaseOmega(btVector3(0, 0, 0));
    part.mb->clearForcesAndTorques();
    part.mb->clearConstraintForces();
  }
  std::fill(s_->ext_force.begin(), s_->ext_force.end(), Eigen::Vector3d::Zero());
  std::fill(s_->ext_torque.begin(), s_->ext_torque.end(), Eigen::Vector3d::Zero());
  s_->has_ext_wrench = false;
  s_->syncColliders();
  s_->wake();
  // Forget contacts (and their warm-start impulses) of the old pose.
  auto* w = s_->world->world.get();
  for (auto& c : s_->colliders) {
    if (c && c->getBroadphaseHandle()) {
      w->getBroadphase()->getOverlappingPairCache()->cleanProxyFromPairs(c->getBroadphaseHandle(),
                                                                         w->getDispatcher());
    }
  }
}

const Eigen::Isometry3d& PhysicsRobot::spawnPose() const { return s_->spawn; }
const std::vector<std::string>& PhysicsRobot::linkNames() const { return s_->link_names; }

Eigen::Isometry3d PhysicsRobot::linkPose(const std::string& link) const {
  auto it = s_->tree.links.find(link);
  if (it == s_->tree.links.end()) {
    throw PhysicsError("robot '" + s_->name + "': unknown link '" + link + "'");
  }
  const int b = it->second.first;
  return toEigen(s_->comFrame(b)) * s_->X_BC[b].inverse() * it->second.second;
}

Twist PhysicsRobot::linkTwist(const std::string& link) const {
  const int b = s_->bodyOf(link);
  return s_->bodyTwistAt(b, linkPose(link).translation());
}

void PhysicsRobot::setExternalWrench(const std::string& link, const Eigen::Vector3d& force_W,
                                     const Eigen::Vector3d& torque_W) {
  const int b = s_->bodyOf(link);
  if (!force_W.allFinite() || !torque_W.allFinite()) {
    ++s_->rejected;
    return;
  }
  s_->ext_force[b] = force_W;
  s_->ext_torque[b] = torque_W;
  s_->has_ext_wrench = false;
  for (std::size_t k = 0; k < s_->ext_force.size(); ++k) {
    if (!s_->ext_force[k].isZero(0.0) || !s_->ext_torque[k].isZero(0.0)) s_->has_ext_wrench = true;
  }
  s_->wake();
}

void PhysicsRobot::allowSleep(bool allow) {
  const PhysicsOptions& o = s_->world->options;
  allow = allow && s_->world_model && o.sleep_time > 0.0;
  for (const RobotState::Part& part : s_->parts) {
    // Gazebo: links of a model with joints never auto-disable.
    const bool can = allow && part.mb->getNumLinks() == 0 && !part.mb->hasFixedBase();
    part.mb->setCanSleep(can);
    part.mb->setSleepThreshold(o.sleep_speed * o.sleep_speed);
    part.mb->setSleepTimeout(o.sleep_time);
    part.mb->wakeUp();
  }
  for (std::size_t b = 0; b < s_->colliders.size(); ++b) {
    btCollisionObject* c = s_->colliders[b].get();
    if (c == nullptr || c->isStaticObject()) continue;
    c->forceActivationState(s_->mbOfBody(static_cast<int>(b))->getCanSleep() ? ACTIVE_TAG
                                                                             : DISABLE_DEACTIVATION);
  }
}

bool PhysicsRobot::asleep() const {
  bool any = false;
  for (const RobotState::Part& part : s_->parts) {
    if (!part.mb->getCanSleep()) continue;
    const btCollisionObject* c = part.mb->getBaseCollider();
    if (c == nullptr || c->getActivationState() != ISLAND_SLEEPING) return false;
    any = true;
  }
  return any;
}

void PhysicsRobot::wake() { s_->wake(); }

int PhysicsRobot::contactCount(const std::string& link, double max_distance) const {
  const int b = s_->bodyOf(link);
  const btCollisionObject* col = s_->colliders[b].get();
  if (col == nullptr) return 0;
  btDispatcher* d = s_->world->world->getDispatcher();
  int count = 0;
  for (int m = 0; m < d->getNumManifolds(); ++m) {
    const btPersistentManifold* pm = d->getManifoldByIndexInternal(m);
    if (pm->getBody0() != col && pm->getBody1() != col) continue;
    for (int p = 0; p < pm->getNumContacts(); ++p) {
      if (pm->getContactPoint(p).getDistance() <= max_distance) ++count;
    }
  }
  return count;
}

double PhysicsRobot::contactNormalForce(const std::string& link) const {
  const int b = s_->bodyOf(link);
  const btCollisionObject* col = s_->colliders[b].get();
  if (col == nullptr) return 0.0;
  btDispatcher* d = s_->world->world->getDispatcher();
  double impulse = 0.0;
  for (int m = 0; m < d->getNumManifolds(); ++m) {
    const btPersistentManifold* pm = d->getManifoldByIndexInternal(m);
    if (pm->getBody0() != col && pm->getBody1() != col) continue;
    for (int p = 0; p < pm->getNumContacts(); ++p) {
      const btManifoldPoint& cp = pm->getContactPoint(p);
      // Points beyond the processing threshold are not solved and keep stale impulses.
      if (cp.getDistance() <= pm->getContactProcessingThreshold()) impulse += cp.getAppliedImpulse();
    }
  }
  return impulse / s_->world->options.dt;
}

double PhysicsRobot::kineticEnergy() const {
  auto body = [&](double m, const btVector3& I, const btVector3& w, const btVector3& v) {
    return 0.5 * m * v.length2() + 0.5 * (I.x() * w.x() * w.x() + I.y() * w.y() * w.y() +
                                          I.z() * w.z() * w.z());
  };
  double e = 0.0;
  for (const RobotState::Part& part : s_->parts) {
    const btMultiBody& mb = *part.mb;
    const int n = mb.getNumLinks();
    btAlignedObjectArray<btVector3> omega, vel;
    omega.resize(n + 1);
    vel.resize(n + 1);
    mb.compTreeLinkVelocities(&omega[0], &vel[0]);
    e += body(mb.getBaseMass(), mb.getBaseInertia(), omega[0], vel[0]);
    for (int i = 0; i < n; ++i) e += body(mb.getLinkMass(i), mb.getLinkInertia(i), omega[i + 1], vel[i + 1]);
  }
  return e;
}

double PhysicsRobot::potentialEnergy() const {
  const Eigen::Vector3d g = s_->world->options.gravity;
  double e = 0.0;
  for (std::size_t b = 0; b < s_->tree.bodies.size(); ++b) {
    const Eigen::Vector3d p = toEigen(s_->comFrame(static_cast<int>(b)).getOrigin());
    e -= s_->tree.bodies[b].mass.mass * g.dot(p);
    const MassProperties& free = s_->tree.bodies[b].gravity_free;  // feels no gravity
    if (free.mass > 0.0) {
      const btTransform X_WC = s_->comFrame(static_cast<int>(b));
      e += free.mass * g.dot(toEigen(X_WC(toBt(s_->gravity_free_com_C[b]))));
    }
  }
  return e;
}

double PhysicsRobot::totalMass() const {
  double m = 0.0;
  for (const auto& b : s_->tree.bodies) m += b.mass.mass;
  return m;
}

const btCollisionObject* PhysicsRobot::collisionObject(const std::string& link) const {
  const int b = s_->bodyOf(link);
  return s_->tree.bodies[b].collisions.empty() ? nullptr : s_->colliders[b].get();
}

}  // namespace tianracer_sim
