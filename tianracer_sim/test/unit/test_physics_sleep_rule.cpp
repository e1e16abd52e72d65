// multiBodyAsleep (src/physics/bullet.h) against Bullet itself: btMultiBodyDynamicsWorld adds
// gravity to, and integrates, a multibody only when none of its colliders (base or link) is
// ISLAND_SLEEPING. applyGravityFree and RobotState::wake follow the same rule, so the force
// they add or clear is the one Bullet adds. Bullet alone here, no PhysicsWorld.
#include <gtest/gtest.h>

#include <memory>
#include <vector>

#include "../../src/physics/bullet.h"

namespace tianracer_sim {
namespace {

// A floating base and one revolute link, each with a sphere collider, in a world without
// contacts (nothing else in it).
struct TwoColliderBody {
  btDefaultCollisionConfiguration config;
  btCollisionDispatcher dispatcher{&config};
  btDbvtBroadphase broadphase;
  btMultiBodyConstraintSolver solver;
  btMultiBodyDynamicsWorld world{&dispatcher, &broadphase, &solver, &config};
  btSphereShape sphere{0.1};
  btMultiBody mb{1, 1.0, btVector3(0.01, 0.01, 0.01), false, false};
  std::unique_ptr<btMultiBodyLinkCollider> base, link;

  TwoColliderBody() {
    world.setGravity(btVector3(0, 0, -10));
    mb.setupRevolute(0, 1.0, btVector3(0.01, 0.01, 0.01), -1, btQuaternion::getIdentity(),
                     btVector3(0, 0, 1), btVector3(0.5, 0, 0), btVector3(0.5, 0, 0), true);
    mb.finalizeMultiDof();
    mb.setBaseWorldTransform(btTransform::getIdentity());
    world.addMultiBody(&mb);
    base = std::make_unique<btMultiBodyLinkCollider>(&mb, -1);
    base->setCollisionShape(&sphere);
    base->setWorldTransform(btTransform::getIdentity());
    world.addCollisionObject(base.get());
    mb.setBaseCollider(base.get());
    link = std::make_unique<btMultiBodyLinkCollider>(&mb, 0);
    link->setCollisionShape(&sphere);
    link->setWorldTransform(btTransform(btQuaternion::getIdentity(), btVector3(1, 0, 0)));
    world.addCollisionObject(link.get());
    mb.getLink(0).m_collider = link.get();
    mb.setCanSleep(false);  // the island manager leaves the states as the test sets them
    base->forceActivationState(ACTIVE_TAG);
    link->forceActivationState(ACTIVE_TAG);
  }
  /// The base's vertical speed after one step.
  double vzAfterAStep() {
    world.stepSimulation(0.01, 0, 0.01);
    return mb.getBaseVel().z();
  }
  ~TwoColliderBody() {
    world.removeCollisionObject(link.get());
    world.removeCollisionObject(base.get());
    world.removeMultiBody(&mb);
  }
};

TEST(SleepRule, AwakeWhenEveryColliderIsAwakeAndBulletAddsGravity) {
  TwoColliderBody b;
  EXPECT_FALSE(multiBodyAsleep(b.mb));
  EXPECT_LT(b.vzAfterAStep(), -0.05);  // falls: -g dt = -0.1
}

TEST(SleepRule, ASleepingLinkColliderIsAsleepAndBulletAddsNoGravity) {
  TwoColliderBody b;
  b.link->forceActivationState(ISLAND_SLEEPING);  // the base stays awake
  EXPECT_TRUE(multiBodyAsleep(b.mb));
  EXPECT_EQ(b.vzAfterAStep(), 0.0);
}

TEST(SleepRule, ASleepingBaseColliderIsAsleepAndBulletAddsNoGravity) {
  TwoColliderBody b;
  b.base->forceActivationState(ISLAND_SLEEPING);
  EXPECT_TRUE(multiBodyAsleep(b.mb));
  EXPECT_EQ(b.vzAfterAStep(), 0.0);
}

TEST(SleepRule, NoCollidersIsAwake) {
  btMultiBody mb(0, 1.0, btVector3(0.01, 0.01, 0.01), false, false);
  mb.finalizeMultiDof();
  EXPECT_FALSE(multiBodyAsleep(mb));
}

}  // namespace
}  // namespace tianracer_sim
