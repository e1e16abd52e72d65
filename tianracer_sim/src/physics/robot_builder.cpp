// Building a robot's Bullet multibody from its rigid tree, and taking it out again.
#include <cmath>

#include "world_impl.h"

namespace tianracer_sim {

void PhysicsWorld::Impl::buildRobot(RobotState* r, const SurfaceOf& surface_of) {
  const RigidTree& tree = r->tree;
  const int nb = static_cast<int>(tree.bodies.size());

  // Principal COM frames.
  std::vector<Eigen::Vector3d> moments(nb);
  r->X_BC.assign(nb, Eigen::Isometry3d::Identity());
  for (int b = 0; b < nb; ++b) {
    const MassProperties& m = tree.bodies[b].mass;
    if (m.mass > 0.0) {
      const PrincipalInertia p = principalInertia(m.inertia);
      moments[b] = p.moments;
      r->X_BC[b].linear() = p.R;
      r->X_BC[b].translation() = m.com;
    } else {
      moments[b].setZero();
    }
  }
  // The gravity-free masses' COMs in C (applyGravityFree).
  r->gravity_free_com_C.assign(nb, Eigen::Vector3d::Zero());
  r->has_gravity_free = false;
  for (int b = 0; b < nb; ++b) {
    const MassProperties& free = tree.bodies[b].gravity_free;
    if (!(free.mass > 0.0)) continue;
    r->has_gravity_free = true;
    r->gravity_free_com_C[b] = r->X_BC[b].inverse() * free.com;
  }

  // One multibody per tree: parts[k] has its base at a body with parent == -1 and the
  // bodies after it (up to the next root) as links.
  r->body_part.assign(nb, 0);
  r->body_link.assign(nb, -1);
  for (int b = 0; b < nb; ++b) {
    const TreeBody& body = tree.bodies[b];
    if (body.parent < 0) {
      RobotState::Part part;
      part.root = b;
      r->parts.push_back(std::move(part));
    } else if (body.parent >= b || body.parent < r->parts.back().root) {
      throw PhysicsError("robot '" + r->name + "': body '" + body.link +
                         "' does not follow its parent in its tree");
    }
    r->body_part[b] = static_cast<int>(r->parts.size()) - 1;
    r->body_link[b] = b - r->parts.back().root - 1;
  }
  if (r->parts.empty() || r->parts[0].root != 0) {
    throw PhysicsError("robot '" + r->name + "': body 0 is not a root");
  }
  std::size_t max_bodies = 0;
  for (std::size_t k = 0; k < r->parts.size(); ++k) {
    RobotState::Part& part = r->parts[k];
    const int end = k + 1 < r->parts.size() ? r->parts[k + 1].root : nb;
    const int nlinks = end - part.root - 1;
    max_bodies = std::max(max_bodies, static_cast<std::size_t>(nlinks + 1));
    const TreeBody& root = tree.bodies[part.root];
    const bool fixed = part.root == 0 && tree.fixed_base;
    part.mb = std::make_unique<btMultiBody>(nlinks, fixed ? 0.0 : root.mass.mass,
                                            toBt(moments[part.root]), fixed, false);
    btMultiBody* mb = part.mb.get();
    mb->setBaseName(nullptr);
    for (int b = part.root + 1; b < end; ++b) {
      const TreeBody& body = tree.bodies[b];
      const int link = r->body_link[b], parent_link = r->body_link[body.parent];
      const Eigen::Isometry3d X_PcB = r->X_BC[body.parent].inverse() * body.X_PB;  // joint in Pc
      const Eigen::Isometry3d X_CcB = r->X_BC[b].inverse();                         // joint in Cc
      const btQuaternion rot_parent_to_this =
          toBtQuat(X_CcB.linear() * X_PcB.linear().transpose());
      const btVector3 axis_C = toBt(Eigen::Vector3d(X_CcB.linear() * body.axis_B));
      const btVector3 parent_com_to_pivot = toBt(Eigen::Vector3d(X_PcB.translation()));
      const btVector3 pivot_to_com = toBt(Eigen::Vector3d(-X_CcB.translation()));
      if (body.joint_type == TreeJointType::kPrismatic) {
        mb->setupPrismatic(link, body.mass.mass, toBt(moments[b]), parent_link,
                           rot_parent_to_this, axis_C, parent_com_to_pivot, pivot_to_com, true);
      } else {
        mb->setupRevolute(link, body.mass.mass, toBt(moments[b]), parent_link,
                          rot_parent_to_this, axis_C, parent_com_to_pivot, pivot_to_com, true);
      }
    }
    mb->finalizeMultiDof();
    // Gazebo/ODE have no velocity damping and no speed cap.
    mb->setLinearDamping(0.0);
    mb->setAngularDamping(0.0);
    mb->setMaxCoordinateVelocity(1e4);
    // Links of a robot never collide with each other (Gazebo's URDF import sets no
    // self_collide); a world model's may (WorldModelFilter).
    bool self_collide = false;
    for (int b = part.root; b < end; ++b) self_collide = self_collide || tree.bodies[b].self_collide;
    mb->setHasSelfCollision(r->world_model && self_collide);
    mb->setCanSleep(false);
    mb->setUseGyroTerm(true);
    world->addMultiBody(mb);
  }

  // Colliders, one per body with collisions: a compound in the COM frame.
  r->colliders.resize(nb);
  int collision_index = 0;
  std::vector<Eigen::Isometry3d> X_MB(nb);  // bodies in the model frame at q = 0
  for (int b = 0; b < nb; ++b) {
    const TreeBody& body = tree.bodies[b];
    X_MB[b] = body.parent < 0 ? body.X_PB : X_MB[body.parent] * body.X_PB;
    if (body.collisions.empty()) {
      // Bullet files a joint motor or limit under the island of its link's collider and skips
      // it when there is none: a body without geometry gets a 1 mm sphere that collides with
      // nothing (mask 0).
      auto sphere = std::make_unique<btSphereShape>(1e-3);
      auto surfaces = std::make_unique<ColliderSurfaces>();
      surfaces->children.emplace_back();
      auto col = std::make_unique<btMultiBodyLinkCollider>(r->mbOfBody(b), r->body_link[b]);
      col->setCollisionShape(sphere.get());
      col->setActivationState(DISABLE_DEACTIVATION);
      col->setUserPointer(surfaces.get());
      col->setUserIndex(r->user_index);
      col->setUserIndex2(b);
      world->addCollisionObject(col.get(), btBroadphaseProxy::DefaultFilter, 0);
      if (r->body_link[b] < 0) {
        r->mbOfBody(b)->setBaseCollider(col.get());
      } else {
        r->mbOfBody(b)->getLink(r->body_link[b]).m_collider = col.get();
      }
      r->shapes.push_back(std::move(sphere));
      r->surfaces.push_back(std::move(surfaces));
      r->colliders[b] = std::move(col);
      continue;
    }
    auto compound = std::make_unique<btCompoundShape>(false, static_cast<int>(body.collisions.size()));
    auto surfaces = std::make_unique<ColliderSurfaces>();
    const Eigen::Isometry3d X_CB = r->X_BC[b].inverse();
    bool all_wheels = true;
    // A world model's bodies welded to the world are static (ODE gives them no body).
    const bool welded = r->world_model && b == 0 && tree.fixed_base;
    for (const CollisionGeometry& g : body.collisions) {
      Eigen::Isometry3d X_BS;
      bool is_wheel = false;
      std::unique_ptr<OwnedShape> mesh;
      std::unique_ptr<btCollisionShape> shape = makeLinkShape(
          body, g, options.collision_margin,
          // A world model's wheel is fitted (one contact under the axle) only while its axle
          // is level: a cambered cylinder touches with its rim, lower than R (polaris: 1.52
          // rad, 7 mm), and Gazebo collides the true cylinder.
          !r->world_model || std::abs((X_MB[b].linear() * body.axis_B).z()) < 1e-3
              ? options.wheel_shape
              : WheelShape::kMeshHull,
          r->world_model,  // a world model's meshes are concave, as in Gazebo
          (r->world_model ? "model '" : "robot '") + r->name + "' link '" + g.link + "'", &X_BS,
          &is_wheel, &mesh);
      if (mesh) r->meshes.push_back(std::move(mesh));
      all_wheels = all_wheels && is_wheel;
      compound->addChildShape(toBt(Eigen::Isometry3d(X_CB * X_BS)), shape.get());
      const Eigen::Matrix3d R_CL = X_CB.linear() * body.X_BL.at(g.link).linear();
      const SurfaceParams params = surface_of(g, collision_index++);
      surfaces->children.push_back(toSurface(params, R_CL, options.contact_max_vel));
      // The object's masks: the union of its collisions' (PhysicsWorld's filter).
      const bool first = surfaces->children.size() == 1;
      surfaces->collide_bitmask = (first ? 0u : surfaces->collide_bitmask) | params.collide_bitmask;
      surfaces->without_contact_bitmask =
          (first ? 0u : surfaces->without_contact_bitmask) | params.collide_without_contact_bitmask;
      surfaces->without_contact = (first || surfaces->without_contact) && params.collide_without_contact;
      r->shapes.push_back(std::move(shape));
    }
    surfaces->body = !welded;
    auto col = std::make_unique<btMultiBodyLinkCollider>(r->mbOfBody(b), r->body_link[b]);
    col->setCollisionShape(compound.get());
    setAnisotropy(col.get(), *surfaces);
    col->setCollisionFlags(col->getCollisionFlags() | btCollisionObject::CF_CUSTOM_MATERIAL_CALLBACK |
                           (welded ? btCollisionObject::CF_STATIC_OBJECT : 0) |
                           // Every collision of the body collides without contact: Bullet finds
                           // its contacts (bumpers read them) but solves none.
                           (surfaces->without_contact ? btCollisionObject::CF_NO_CONTACT_RESPONSE : 0));
    col->setActivationState(DISABLE_DEACTIVATION);
    col->setFriction(surfaces->children[0].mu1);
    col->setRestitution(0.0);
    col->setRollingFriction(0.0);
    col->setSpinningFriction(0.0);
    col->setUserPointer(surfaces.get());
    col->setUserIndex(r->user_index);
    col->setUserIndex2(b);
    if (r->world_model && body.self_collide) col->setUserIndex3(1);
    if (all_wheels) {
      // A rolling wheel's manifold keeps up to 3 stale points behind the contact (rising off
      // the ground, 0.01-1 mm up) which Bullet would solve as speculative contacts: 4x the rows
      // and a little drag. The narrowphase finds the true contact afresh every step, so only
      // touching points are solved for wheels.
      col->setContactProcessingThreshold(0.0);
      surfaces->wheel = true;
    }
    if (welded) {
      world->addCollisionObject(col.get(), btBroadphaseProxy::StaticFilter,
                                btBroadphaseProxy::AllFilter ^ btBroadphaseProxy::StaticFilter);
    } else {
      world->addCollisionObject(col.get(), btBroadphaseProxy::DefaultFilter,
                                btBroadphaseProxy::AllFilter);
    }
    if (r->body_link[b] < 0) {
      r->mbOfBody(b)->setBaseCollider(col.get());
    } else {
      r->mbOfBody(b)->getLink(r->body_link[b]).m_collider = col.get();
    }
    r->shapes.push_back(std::move(compound));
    r->surfaces.push_back(std::move(surfaces));
    r->colliders[b] = std::move(col);
  }

  // Tyres: stiffness as given, damping from the damping ratio of one wheel carrying its share
  // of the robot's mass on that spring, kd = 2 zeta sqrt(k m / wheels).
  int wheels = 0;
  double mass = 0.0;
  for (int b = 0; b < nb; ++b) {
    mass += tree.bodies[b].mass.mass;
    if (r->surfaces[b]->wheel) ++wheels;
  }
  for (auto& sf : r->surfaces) {
    if (r->world_model || !sf->wheel || !(options.tyre_stiffness > 0.0)) continue;  // no tyres on models
    sf->tyre_stiffness = options.tyre_stiffness;
    sf->tyre_damping =
        2.0 * options.tyre_damping_ratio * std::sqrt(options.tyre_stiffness * mass / wheels);
  }

  // Joints: info, limits, motors (added to the world when first used).
  for (int b = 1; b < nb; ++b) {
    const TreeBody& body = tree.bodies[b];
    if (body.parent < 0) continue;  // the root of another tree
    JointInfo j;
    j.name = body.joint;
    j.type = body.joint_type == TreeJointType::kRevolute
                 ? JointType::kRevolute
                 : (body.joint_type == TreeJointType::kPrismatic ? JointType::kPrismatic
                                                                 : JointType::kContinuous);
    j.parent_link = tree.bodies[body.parent].link;
    j.child_link = body.link;
    j.axis = body.axis_B;
    j.has_position_limits = body.has_position_limits;
    j.lower = body.lower;
    j.upper = body.upper;
    j.effort_limit = body.effort_limit;
    j.velocity_limit = body.velocity_limit;
    j.damping = body.damping;
    j.friction = body.friction;
    j.spring_stiffness = body.spring_stiffness;
    j.spring_reference = body.spring_reference;
    j.motor_effort = body.effort_limit > 0.0 ? body.effort_limit : options.default_motor_effort;
    r->joint_index[j.name] = static_cast<int>(r->joints.size());
    r->joints.push_back(j);
    r->joint_body.push_back(b);
    // Limit, motor and damper constraints are made when first used (applyCommands).
    r->limits.emplace_back();
    r->limit_in_world.push_back(false);
    r->motors.emplace_back();
    r->motor_in_world.push_back(false);
    r->dampers.emplace_back();
    r->damper_in_world.push_back(false);
  }
  r->commands.assign(r->joints.size(), RobotState::Command());
  r->applied_effort.assign(r->joints.size(), 0.0);
  r->ext_effort.assign(r->joints.size(), 0.0);
  for (const TreeBody& body : tree.bodies) {
    for (const auto& l : body.merged_links) r->link_names.push_back(l);
  }
  r->scratch_q.resize(static_cast<int>(max_bodies));
  r->scratch_p.resize(static_cast<int>(max_bodies));
  r->scratch_w.resize(static_cast<int>(max_bodies));
  r->scratch_v.resize(static_cast<int>(max_bodies));
  r->ext_force.assign(nb, Eigen::Vector3d::Zero());
  r->ext_torque.assign(nb, Eigen::Vector3d::Zero());
}

void PhysicsWorld::Impl::removeFromWorld(RobotState* r) {
  for (std::size_t j = 0; j < r->motors.size(); ++j) {
    if (r->motor_in_world[j]) world->removeMultiBodyConstraint(r->motors[j].get());
  }
  for (std::size_t k = 0; k < r->limits.size(); ++k) {
    if (r->limit_in_world[k]) world->removeMultiBodyConstraint(r->limits[k].get());
  }
  for (std::size_t k = 0; k < r->dampers.size(); ++k) {
    if (r->damper_in_world[k]) world->removeMultiBodyConstraint(r->dampers[k].get());
  }
  for (auto& c : r->colliders) {
    if (c) world->removeCollisionObject(c.get());
  }
  for (auto& part : r->parts) {
    if (part.mb) world->removeMultiBody(part.mb.get());
  }
}

}  // namespace tianracer_sim
