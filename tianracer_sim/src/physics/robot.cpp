// The robot API (PhysicsRobot) and how its commands reach Bullet each step.
#include <algorithm>
#include <cassert>
#include <cmath>

#include "world_impl.h"

namespace tianracer_sim {

btTransform RobotState::comFrame(int b) const {
  if (b == 0) return mb->getBaseWorldTransform();
  mb->forwardKinematics(scratch_q, scratch_p);
  const btQuaternion& q = scratch_q[b];
  return btTransform(q.inverse(), scratch_p[b]);
}

void RobotState::syncColliders() {
  mb->forwardKinematics(scratch_q, scratch_p);
  mb->updateCollisionObjectWorldTransforms(scratch_q, scratch_p);
  for (auto& c : colliders) {
    if (c) world->world->updateSingleAabb(c.get());
  }
}

void PhysicsWorld::Impl::applyCommands(RobotState* r) {
  const double dt = options.dt;
  // A limit constraint costs two solver rows every step, also far from the limit: it joins the
  // solve only while the joint is within 0.05 rad (or two steps of travel) of either end, so it
  // cannot be crossed unseen.
  for (std::size_t k = 0; k < r->limits.size(); ++k) {
    const JointInfo& j = r->joints[r->limit_joint[k]];
    const int link = r->limit_joint[k];
    const double q = r->mb->getJointPos(link);
    const double margin = 0.05 + 2.0 * std::abs(r->mb->getJointVel(link)) * dt;
    const bool near = q - j.lower < margin || j.upper - q < margin;
    if (near != r->limit_in_world[k]) {
      if (near) {
        world->addMultiBodyConstraint(r->limits[k].get());
      } else {
        world->removeMultiBodyConstraint(r->limits[k].get());
      }
      r->limit_in_world[k] = near;
    }
  }
  for (std::size_t i = 0; i < r->joints.size(); ++i) {
    const JointInfo& j = r->joints[i];
    const RobotState::Command& c = r->commands[i];
    const int link = static_cast<int>(i);
    double tau = c.mode == RobotState::Mode::kEffort ? c.effort : 0.0;
    if (j.damping > 0.0) tau -= j.damping * r->mb->getJointVel(link);
    if (tau != 0.0) r->mb->addJointTorque(link, tau);

    btMultiBodyJointMotor* motor = r->motors[i].get();
    double target = 0.0, max_impulse = 0.0;
    if (c.mode == RobotState::Mode::kVelocity) {
      target = c.velocity;
      max_impulse = c.max_effort * dt;
    } else if (j.friction > 0.0) {
      max_impulse = j.friction * dt;
    }
    if (max_impulse > 0.0 && !r->motor_in_world[i]) {
      world->addMultiBodyConstraint(motor);
      r->motor_in_world[i] = true;
    }
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
  return s_->mb->getJointPos(i);
}
double PhysicsRobot::jointVelocity(int i) const {
  checkJoint(s_, i);
  return s_->mb->getJointVel(i);
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
  s_->mb->setJointPos(i, position);
  s_->mb->setJointVel(i, velocity);
  s_->syncColliders();
}

std::uint64_t PhysicsRobot::rejectedCommands() const { return s_->rejected; }

Eigen::Isometry3d PhysicsRobot::basePose() const {
  return toEigen(s_->mb->getBaseWorldTransform()) * s_->X_BC[0].inverse();
}

Twist PhysicsRobot::baseTwist() const {
  Twist t;
  t.angular = toEigen(s_->mb->getBaseOmega());
  const Eigen::Vector3d v_com = toEigen(s_->mb->getBaseVel());
  const btTransform X_WC = s_->mb->getBaseWorldTransform();
  const Eigen::Vector3d p_com = toEigen(X_WC.getOrigin());
  const Eigen::Vector3d p_origin = basePose().translation();
  t.linear = v_com + t.angular.cross(p_origin - p_com);
  return t;
}

void PhysicsRobot::setBasePose(const Eigen::Isometry3d& X_WB) {
  if (!X_WB.matrix().allFinite()) {
    ++s_->rejected;
    return;
  }
  Eigen::Isometry3d X = X_WB;
  X.linear() = Eigen::Quaterniond(X_WB.rotation()).normalized().toRotationMatrix();
  s_->mb->setBaseWorldTransform(toBt(Eigen::Isometry3d(X * s_->X_BC[0])));
  s_->syncColliders();
}

void PhysicsRobot::setBaseTwist(const Twist& twist) {
  if (!twist.linear.allFinite() || !twist.angular.allFinite()) {
    ++s_->rejected;
    return;
  }
  const Eigen::Vector3d p_com = toEigen(s_->mb->getBaseWorldTransform().getOrigin());
  const Eigen::Vector3d p_origin = basePose().translation();
  s_->mb->setBaseVel(toBt(Eigen::Vector3d(twist.linear + twist.angular.cross(p_com - p_origin))));
  s_->mb->setBaseOmega(toBt(twist.angular));
}

void PhysicsRobot::resetToSpawn() {
  for (std::size_t i = 0; i < s_->joints.size(); ++i) {
    s_->mb->setJointPos(static_cast<int>(i), 0.0);
    s_->mb->setJointVel(static_cast<int>(i), 0.0);
    s_->commands[i] = RobotState::Command();
    s_->applied_effort[i] = 0.0;
  }
  s_->mb->setBaseWorldTransform(toBt(Eigen::Isometry3d(s_->spawn * s_->X_BC[0])));
  s_->mb->setBaseVel(btVector3(0, 0, 0));
  s_->mb->setBaseOmega(btVector3(0, 0, 0));
  s_->mb->clearForcesAndTorques();
  s_->mb->clearConstraintForces();
  s_->syncColliders();
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
  const btMultiBody& mb = *s_->mb;
  const int n = mb.getNumLinks();
  btAlignedObjectArray<btVector3> omega, vel;
  omega.resize(n + 1);
  vel.resize(n + 1);
  mb.compTreeLinkVelocities(&omega[0], &vel[0]);
  auto body = [&](double m, const btVector3& I, const btVector3& w, const btVector3& v) {
    return 0.5 * m * v.length2() + 0.5 * (I.x() * w.x() * w.x() + I.y() * w.y() * w.y() +
                                          I.z() * w.z() * w.z());
  };
  double e = body(mb.getBaseMass(), mb.getBaseInertia(), omega[0], vel[0]);
  for (int i = 0; i < n; ++i) e += body(mb.getLinkMass(i), mb.getLinkInertia(i), omega[i + 1], vel[i + 1]);
  return e;
}

double PhysicsRobot::potentialEnergy() const {
  const Eigen::Vector3d g = s_->world->options.gravity;
  double e = 0.0;
  for (std::size_t b = 0; b < s_->tree.bodies.size(); ++b) {
    const Eigen::Vector3d p = toEigen(s_->comFrame(static_cast<int>(b)).getOrigin());
    e -= s_->tree.bodies[b].mass.mass * g.dot(p);
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
