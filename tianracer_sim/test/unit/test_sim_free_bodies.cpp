// Free rigid bodies from a world's dynamic models: free fall and landing, sliding friction,
// contact softness from <contact><ode>, merged links, reset, determinism and the scene poses
// sensors see. Joints, separate links and bad mass properties: test_sim_world_models.cpp.
#include <gtest/gtest.h>

#include <cmath>
#include <iostream>
#include <string>
#include <vector>

#include "tianracer_sim/sim/simulation.h"
#include "tianracer_sim/sim/world_physics.h"
#include "tianracer_sim/world/world.h"

namespace tianracer_sim {
namespace {

constexpr double kG = 9.8;

/// A dynamic box model "<name>" of size sx sy sz and mass m at pose, with optional surface XML.
std::string boxModel(const std::string& name, const Eigen::Vector3d& size, double m,
                     const std::string& pose, const std::string& surface = "") {
  const double ixx = m / 12 * (size.y() * size.y() + size.z() * size.z());
  const double iyy = m / 12 * (size.x() * size.x() + size.z() * size.z());
  const double izz = m / 12 * (size.x() * size.x() + size.y() * size.y());
  const std::string s = std::to_string(size.x()) + " " + std::to_string(size.y()) + " " +
                        std::to_string(size.z());
  return "<model name='" + name + "'><pose>" + pose + "</pose><link name='link'><inertial><mass>" +
         std::to_string(m) + "</mass><inertia><ixx>" + std::to_string(ixx) + "</ixx><iyy>" +
         std::to_string(iyy) + "</iyy><izz>" + std::to_string(izz) +
         "</izz></inertia></inertial><collision name='c'><geometry><box><size>" + s +
         "</size></box></geometry>" + surface + "</collision><visual name='v'><geometry><box><size>" +
         s + "</size></box></geometry></visual></link></model>";
}

WorldDescription world(const std::string& models) {
  return loadWorldString("<sdf version='1.6'><world name='w'><include><uri>model://ground_plane"
                         "</uri></include>" + models + "</world></sdf>",
                         "test.world", ".");
}

std::string friction(double mu) {
  return "<surface><friction><ode><mu>" + std::to_string(mu) + "</mu><mu2>" + std::to_string(mu) +
         "</mu2></ode></friction></surface>";
}

struct FreeWorld {
  WorldDescription desc;
  PhysicsWorld physics;
  std::vector<std::string> warnings;
  explicit FreeWorld(const std::string& models)
      : desc(world(models)), physics(physicsOptionsFor(desc)) {
    addWorldToPhysics(desc, &physics, [this](const std::string& w) { warnings.push_back(w); });
  }
};

TEST(FreeBodies, BoxDroppedFromOneMetreLandsOnTimeAndRestsOnAFace) {
  // Tilted 20 deg and 10 deg so that it lands on an edge and must tip over onto a face; its
  // lowest corner starts 1 m above the ground.
  const Eigen::Vector3d size(0.2, 0.3, 0.1);
  const Eigen::Matrix3d R = (Eigen::AngleAxisd(0.0, Eigen::Vector3d::UnitZ()) *
                             Eigen::AngleAxisd(10 * M_PI / 180, Eigen::Vector3d::UnitY()) *
                             Eigen::AngleAxisd(20 * M_PI / 180, Eigen::Vector3d::UnitX()))
                                .toRotationMatrix();
  double lowest = 0.0;  // lowest corner below the centre
  for (int k = 0; k < 8; ++k) {
    const Eigen::Vector3d c(((k & 1) ? 0.5 : -0.5) * size.x(), ((k & 2) ? 0.5 : -0.5) * size.y(),
                            ((k & 4) ? 0.5 : -0.5) * size.z());
    lowest = std::min(lowest, (R * c).z());
  }
  const double z0 = 1.0 - lowest;
  FreeWorld w(boxModel("crate", size, 2.0,
                       "0 0 " + std::to_string(z0) + " " + std::to_string(20 * M_PI / 180) + " " +
                           std::to_string(10 * M_PI / 180) + " 0"));
  ASSERT_EQ(w.physics.freeBodyCount(), 1);
  PhysicsRobot& box = w.physics.freeBody(w.physics.freeBodyIndex("crate"));
  double landed = -1.0, vz_prev = 0.0;
  for (int k = 0; k < 3000; ++k) {
    w.physics.step();
    const double vz = box.baseTwist().linear.z();
    // Impact: the first step whose vertical velocity did not grow by g dt downwards.
    if (landed < 0.0 && k > 0 && vz > vz_prev - 0.5 * kG * w.physics.dt()) landed = w.physics.time();
    vz_prev = vz;
  }
  const double expected = std::sqrt(2.0 * 1.0 / kG);
  std::cout << "[box dropped from 1 m] landed after " << landed << " s, sqrt(2h/g) = " << expected
            << " s\n";
  EXPECT_NEAR(landed, expected, 0.01 * expected);
  // At rest on one of its faces: one box axis vertical, the centre at that half extent.
  const Eigen::Isometry3d X = box.basePose();
  int axis = 0;
  for (int i = 1; i < 3; ++i) {
    if (std::abs(X.linear()(2, i)) > std::abs(X.linear()(2, axis))) axis = i;
  }
  std::cout << "[box dropped from 1 m] at rest on the face normal to its axis " << axis
            << ": |cos tilt| " << std::abs(X.linear()(2, axis)) << ", centre z "
            << X.translation().z() << " m (half extent " << 0.5 * size[axis] << ")\n";
  EXPECT_GT(std::abs(X.linear()(2, axis)), 0.9999);
  EXPECT_NEAR(X.translation().z(), 0.5 * size[axis], 1e-3);
  EXPECT_LT(box.baseTwist().linear.norm(), 1e-3);
  EXPECT_LT(box.baseTwist().angular.norm(), 1e-2);
}

// Along a world axis. Bullet's multibody solver takes its two friction rows along fixed
// directions of the contact plane and clamps them to the cone: a diagonal slide falls up to
// ~10 % short of mu g (docs/physics.md, Friction).
TEST(FreeBodies, BoxPushedAlongTheGroundDeceleratesAtMuG) {
  for (const double mu : {0.3, 0.6}) {
    for (const Eigen::Vector3d& v : {Eigen::Vector3d(1.5, 0, 0), Eigen::Vector3d(0, -1.5, 0)}) {
      FreeWorld w(boxModel("crate", Eigen::Vector3d(0.3, 0.3, 0.1), 3.0, "0 0 0.05 0 0 0.4",
                           friction(mu)));
      PhysicsRobot& box = w.physics.freeBody(0);
      for (int k = 0; k < 300; ++k) w.physics.step();  // settle
      box.setBaseTwist({v, Eigen::Vector3d::Zero()});
      for (int k = 0; k < 20; ++k) w.physics.step();
      const double v0 = box.baseTwist().linear.head<2>().norm();
      const int n = 150;
      for (int k = 0; k < n; ++k) w.physics.step();
      const double v1 = box.baseTwist().linear.head<2>().norm();
      const double a = (v0 - v1) / (n * w.physics.dt());
      std::cout << "[box sliding, mu " << mu << ", v " << v.transpose() << "] deceleration " << a
                << " m/s^2, mu g " << mu * kG << " (" << 100.0 * (a / (mu * kG) - 1.0) << " %)\n";
      EXPECT_NEAR(a, mu * kG, 0.03 * mu * kG);
    }
  }
}

// <mu>-1</mu> (Gazebo's library: pr2_gripper, ragdoll) loads and means no limit, as Gazebo's
// FrictionPyramid::SetMu: a box pushed at 1.5 m/s stops at once and nothing goes non-finite.
TEST(FreeBodies, NegativeMuIsFrictionWithoutLimit) {
  FreeWorld w(boxModel("crate", Eigen::Vector3d(0.3, 0.3, 0.1), 3.0, "0 0 0.05 0 0 0",
                       friction(-1.0)));
  ASSERT_EQ(w.desc.models.size(), 1u);
  EXPECT_EQ(w.desc.models[0].links[0].collisions[0].friction.mu, -1.0);
  PhysicsRobot& box = w.physics.freeBody(0);
  for (int k = 0; k < 300; ++k) w.physics.step();  // settle
  const Eigen::Vector3d start = box.basePose().translation();
  box.setBaseTwist({Eigen::Vector3d(1.5, 0, 0), Eigen::Vector3d::Zero()});
  for (int k = 0; k < 20; ++k) w.physics.step();
  const double slid = (box.basePose().translation() - start).head<2>().norm();
  std::cout << "[mu -1] slid " << slid * 100 << " cm in 20 ms, speed "
            << box.baseTwist().linear.norm() << " m/s\n";
  EXPECT_LT(slid, 0.005);  // mu 0.6 slides 2.9 cm in the same 20 ms
  for (int k = 0; k < 1000; ++k) w.physics.step();
  EXPECT_TRUE(box.basePose().matrix().allFinite());
  EXPECT_LT(box.baseTwist().linear.norm(), 0.01);
}

TEST(FreeBodies, ContactStiffnessFromTheWorldFileIsHonoured) {
  // kp 1e4 N/m per contact point (as ODE: each contact joint gets the surfaces' kp) in series
  // with the rigid ground: 2 kg on n points sinks m g / (n kp).
  FreeWorld w(boxModel("soft", Eigen::Vector3d(0.2, 0.2, 0.1), 2.0, "0 0 0.05 0 0 0",
                       "<surface><contact><ode><kp>1e4</kp><kd>100</kd><max_vel>1</max_vel>"
                       "</ode></contact></surface>"));
  PhysicsRobot& box = w.physics.freeBody(0);
  for (int k = 0; k < 3000; ++k) w.physics.step();
  const double sink = 0.05 - box.basePose().translation().z();
  const int n = box.contactCount("link", 0.0);
  const double expected = 2.0 * kG / (n * 1e4);
  std::cout << "[soft box kp 1e4] sinks " << sink * 1e3 << " mm on " << n
            << " contact points (m g / (n kp) = " << expected * 1e3 << " mm)\n";
  ASSERT_GT(n, 0);
  EXPECT_NEAR(sink, expected, 0.1 * expected);
  // The default (rigid) surface sinks far less.
  FreeWorld rigid(boxModel("hard", Eigen::Vector3d(0.2, 0.2, 0.1), 2.0, "0 0 0.05 0 0 0"));
  for (int k = 0; k < 3000; ++k) rigid.physics.step();
  EXPECT_LT(0.05 - rigid.physics.freeBody(0).basePose().translation().z(), 0.2 * expected);
}

TEST(FreeBodies, LinksJoinedByAFixedJointMoveAsOneBody) {
  const std::string model = R"(<model name='stack'><pose>1 2 0.5 0 0 0.3</pose>
    <link name='bottom'><inertial><mass>2</mass><inertia><ixx>0.01</ixx><iyy>0.01</iyy>
      <izz>0.01</izz></inertia></inertial>
      <collision name='c'><geometry><box><size>0.2 0.2 0.2</size></box></geometry></collision></link>
    <link name='top'><pose>0 0 0.15 0 0 0</pose><inertial><mass>1</mass><inertia><ixx>0.001</ixx>
      <iyy>0.001</iyy><izz>0.001</izz></inertia></inertial>
      <collision name='c'><geometry><sphere><radius>0.05</radius></sphere></geometry></collision></link>
    <joint name='glue' type='fixed'><parent>bottom</parent><child>top</child></joint>
  </model>)";
  FreeWorld w(model);
  ASSERT_EQ(w.physics.freeBodyCount(), 1);
  EXPECT_TRUE(w.warnings.empty()) << w.warnings.front();
  PhysicsRobot& body = w.physics.freeBody(0);
  EXPECT_DOUBLE_EQ(body.totalMass(), 3.0);
  for (int k = 0; k < 1500; ++k) w.physics.step();
  const Eigen::Isometry3d X_bottom = body.linkPose("bottom"), X_top = body.linkPose("top");
  EXPECT_NEAR((X_bottom.inverse() * X_top).translation().z(), 0.15, 1e-9);
  EXPECT_NEAR(X_bottom.translation().z(), 0.1, 1e-3);  // fell 0.4 m and rests on the ground
  EXPECT_NEAR(X_bottom.translation().x(), 1.0, 1e-3);
}

TEST(FreeBodies, WithoutCollisionItIsWarnedAbout) {
  FreeWorld w("<model name='ghost'><pose>0 0 1 0 0 0</pose><link name='l'><visual name='v'><geometry>"
              "<sphere><radius>0.1</radius></sphere></geometry></visual></link></model>");
  ASSERT_EQ(w.warnings.size(), 1u);
  EXPECT_NE(w.warnings[0].find("model 'ghost': is dynamic but has no collision"), std::string::npos)
      << w.warnings[0];
}

TEST(FreeBodies, ResetWorldPutsThemBackAndGetModelStateFindsThem) {
  const WorldDescription desc = world(boxModel("crate", Eigen::Vector3d(0.2, 0.2, 0.2), 1.0,
                                               "0.5 0 0.3 0 0 0.2"));
  Simulation sim(physicsOptionsFor(desc));
  addWorldToPhysics(desc, &sim.physics(), {});
  const PhysicsRobot* crate = sim.findModel("crate");
  ASSERT_NE(crate, nullptr);
  EXPECT_EQ(sim.findModel("nothing"), nullptr);
  for (int k = 0; k < 500; ++k) sim.step();
  EXPECT_NEAR(crate->basePose().translation().z(), 0.1, 1e-3);
  sim.resetWorld();
  EXPECT_TRUE(crate->basePose().isApprox(desc.models[0].X_WM, 1e-12));
  EXPECT_EQ(crate->baseTwist().linear.norm(), 0.0);
  for (int k = 0; k < 100; ++k) sim.step();
  sim.resetSimulation();
  EXPECT_EQ(sim.time(), 0.0);
  EXPECT_TRUE(crate->basePose().isApprox(desc.models[0].X_WM, 1e-12));
}

TEST(FreeBodies, SceneBodiesFollowThePhysics) {
  const WorldDescription desc = world(boxModel("crate", Eigen::Vector3d(0.2, 0.2, 0.2), 1.0,
                                               "0.5 0 0.3 0 0 0.2"));
  PhysicsWorld physics(physicsOptionsFor(desc));
  addWorldToPhysics(desc, &physics, {});
  Scene scene;
  const auto bodies = addToScene(desc, scene);
  const int b = bodies.at("crate::link");
  EXPECT_FALSE(scene.bodies[b].is_static);
  physics.freeBody(0).setBaseTwist({Eigen::Vector3d(1, 0, 0), Eigen::Vector3d(0, 0, 2)});
  for (int k = 0; k < 300; ++k) physics.step();
  updateFreeBodyScene(physics, &scene);
  EXPECT_TRUE(scene.bodies[b].X_WB.isApprox(physics.freeBody(0).linkPose("link"), 1e-12));
  EXPECT_GT(scene.bodies[b].X_WB.translation().x(), 0.6);
  EXPECT_TRUE(scene.bodies[bodies.at("ground_plane::link")].X_WB.isApprox(Eigen::Isometry3d::Identity()));
}

TEST(FreeBodies, ManyBoxesStepBitIdentically) {
  std::string models;
  for (int i = 0; i < 12; ++i) {
    models += boxModel("b" + std::to_string(i), Eigen::Vector3d(0.2, 0.2, 0.2), 1.0,
                       std::to_string(0.15 * (i % 4)) + " " + std::to_string(0.15 * (i / 4)) + " " +
                           std::to_string(0.2 + 0.25 * i) + " 0.1 0.2 " + std::to_string(0.3 * i));
  }
  auto run = [&] {
    FreeWorld w(models);
    for (int k = 0; k < 1500; ++k) w.physics.step();
    std::vector<double> out;
    for (int i = 0; i < w.physics.freeBodyCount(); ++i) {
      const Eigen::Isometry3d X = w.physics.freeBody(i).basePose();
      out.insert(out.end(), X.data(), X.data() + 16);
    }
    return out;
  };
  const std::vector<double> a = run(), b = run();
  ASSERT_EQ(a.size(), b.size());
  for (std::size_t i = 0; i < a.size(); ++i) ASSERT_EQ(a[i], b[i]) << i;
}

// The shipped obstacle world: its cones and boxes are free bodies that start at rest where the
// file puts them (no overlap to push apart) and stay upright until something hits them.
TEST(FreeBodies, ShippedObstacleWorldSettlesInPlace) {
  const WorldDescription desc =
      loadWorldFile(resolveWorld("obstacles", std::string(TEST_DATA_DIR) + "/../../worlds"));
  PhysicsWorld physics(physicsOptionsFor(desc));
  std::vector<std::string> warnings;
  addWorldToPhysics(desc, &physics, [&](const std::string& w) { warnings.push_back(w); });
  EXPECT_TRUE(warnings.empty());
  EXPECT_EQ(physics.freeBodyCount(), 10);  // 6 cones, 4 boxes
  for (int k = 0; k < 2000; ++k) physics.step();
  for (int i = 0; i < physics.freeBodyCount(); ++i) {
    const PhysicsRobot& b = physics.freeBody(i);
    const Eigen::Isometry3d X0 = b.spawnPose(), X = b.basePose();
    EXPECT_LT((X.translation() - X0.translation()).norm(), 2e-3) << b.name();
    EXPECT_GT(X.linear()(2, 2), 0.9999) << b.name();
    EXPECT_LT(b.baseTwist().linear.norm(), 1e-3) << b.name();
  }
}

}  // namespace
}  // namespace tianracer_sim

// --- Sleeping (PhysicsOptions::sleep_*, Gazebo's auto-disable) --------------------------------

namespace tianracer_sim {
namespace {

TEST(Sleeping, RestingBodyFallsAsleepWithItsVelocityZeroed) {
  FreeWorld w(boxModel("crate", Eigen::Vector3d(0.2, 0.2, 0.2), 1.0, "0 0 0.4 0.05 0 0"));
  FreeWorld awake(boxModel("crate", Eigen::Vector3d(0.2, 0.2, 0.2), 1.0, "0 0 0.4 0.05 0 0"));
  awake.physics.freeBody(0).allowSleep(false);
  PhysicsRobot& box = w.physics.freeBody(0);
  double fell_asleep = -1.0, last_fast = 0.0;
  for (int k = 0; k < 4000; ++k) {
    w.physics.step();
    awake.physics.step();
    const Twist v = box.baseTwist();
    if (v.linear.squaredNorm() + v.angular.squaredNorm() >=
        std::pow(w.physics.options().sleep_speed, 2)) {
      last_fast = w.physics.time();
    }
    if (fell_asleep < 0.0 && box.asleep()) fell_asleep = w.physics.time();
    // Until it sleeps it moves exactly as a body that may not.
    if (fell_asleep < 0.0) {
      ASSERT_TRUE(box.basePose().isApprox(awake.physics.freeBody(0).basePose(), 0.0)) << k;
    }
  }
  const Eigen::Vector3d p_sleep = box.basePose().translation();
  const Eigen::Vector3d p_awake = awake.physics.freeBody(0).basePose().translation();
  std::cout << "[sleeping] slower than " << w.physics.options().sleep_speed << " from "
            << last_fast << " s, asleep at " << fell_asleep << " s; rests at z " << p_sleep.z()
            << " (never sleeping: " << p_awake.z() << ", " << (p_sleep - p_awake).norm() * 1e6
            << " um apart)\n";
  ASSERT_GT(fell_asleep, 0.0);
  EXPECT_NEAR(fell_asleep - last_fast, w.physics.options().sleep_time, 0.01);
  EXPECT_EQ(box.baseTwist().linear.norm(), 0.0);
  EXPECT_EQ(box.baseTwist().angular.norm(), 0.0);
  EXPECT_LT((p_sleep - p_awake).norm(), 1e-5);
  EXPECT_FALSE(awake.physics.freeBody(0).asleep());
  // Asleep, it stays exactly where it is.
  const Eigen::Isometry3d X = box.basePose();
  for (int k = 0; k < 1000; ++k) w.physics.step();
  EXPECT_TRUE(box.basePose().isApprox(X, 0.0));
  EXPECT_TRUE(box.asleep());
}

TEST(Sleeping, SleepingBodyWakesWhenTouched) {
  // "still" sleeps on the ground; "runner" slides into it along x.
  FreeWorld w(boxModel("still", Eigen::Vector3d(0.2, 0.2, 0.2), 1.0, "0 0 0.1 0 0 0", friction(0.3)) +
              boxModel("runner", Eigen::Vector3d(0.2, 0.2, 0.2), 1.0, "-0.6 0 0.1 0 0 0", friction(0.3)));
  PhysicsRobot& still = w.physics.freeBody(w.physics.freeBodyIndex("still"));
  PhysicsRobot& runner = w.physics.freeBody(w.physics.freeBodyIndex("runner"));
  for (int k = 0; k < 1500; ++k) w.physics.step();
  ASSERT_TRUE(still.asleep());
  ASSERT_TRUE(runner.asleep());
  const Eigen::Vector3d p0 = still.basePose().translation();
  runner.setBaseTwist({Eigen::Vector3d(2.0, 0, 0), Eigen::Vector3d::Zero()});
  EXPECT_FALSE(runner.asleep());
  double woke = -1.0;
  const double t0 = w.physics.time();
  for (int k = 0; k < 1000; ++k) {
    w.physics.step();
    if (woke < 0.0 && !still.asleep() && still.baseTwist().linear.x() > 0.0) woke = w.physics.time() - t0;
  }
  const double moved = still.basePose().translation().x() - p0.x();
  std::cout << "[sleeping] hit by a box at 2 m/s: moving " << woke << " s after the push, pushed "
            << moved << " m\n";
  EXPECT_GT(woke, 0.0);
  EXPECT_GT(moved, 0.05);
}

TEST(Sleeping, SetModelStateAndWrenchesWakeIt) {
  FreeWorld w(boxModel("crate", Eigen::Vector3d(0.2, 0.2, 0.2), 1.0, "0 0 0.1 0 0 0"));
  FreeWorld awake(boxModel("crate", Eigen::Vector3d(0.2, 0.2, 0.2), 1.0, "0 0 0.1 0 0 0"));
  awake.physics.freeBody(0).allowSleep(false);
  PhysicsRobot& box = w.physics.freeBody(0);
  PhysicsRobot& twin = awake.physics.freeBody(0);
  auto sleep = [&] {
    for (int k = 0; k < 3000 && !box.asleep(); ++k) {
      w.physics.step();
      awake.physics.step();
    }
    ASSERT_TRUE(box.asleep());
  };
  sleep();
  // A twist alone (set_model_state with only a velocity): it slides as the twin that never
  // slept.
  const double y0 = box.basePose().translation().y(), y0_twin = twin.basePose().translation().y();
  box.setBaseTwist({Eigen::Vector3d(0, 1, 0), Eigen::Vector3d::Zero()});
  twin.setBaseTwist({Eigen::Vector3d(0, 1, 0), Eigen::Vector3d::Zero()});
  EXPECT_FALSE(box.asleep());
  for (int k = 0; k < 300; ++k) {
    w.physics.step();
    awake.physics.step();
  }
  const double slid = box.basePose().translation().y() - y0;
  const double slid_twin = twin.basePose().translation().y() - y0_twin;
  std::cout << "[sleeping] woken by a twist of 1 m/s: slid " << slid << " m (never asleep: "
            << slid_twin << " m)\n";
  EXPECT_GT(slid, 0.02);
  EXPECT_NEAR(slid, slid_twin, 1e-12);
  sleep();
  // set_model_state: lifted 0.5 m, it falls again.
  Eigen::Isometry3d X = box.basePose();
  X.translation().z() += 0.5;
  box.setBasePose(X);
  EXPECT_FALSE(box.asleep());
  for (int k = 0; k < 200; ++k) w.physics.step();
  EXPECT_LT(box.basePose().translation().z(), 0.6 - 0.1);
  sleep();
  // apply_body_wrench: 20 N sideways (> mu m g = 9.8 N).
  const double x0 = box.basePose().translation().x();
  box.setExternalWrench("link", Eigen::Vector3d(20, 0, 0), Eigen::Vector3d::Zero());
  for (int k = 0; k < 300; ++k) w.physics.step();
  box.setExternalWrench("link", Eigen::Vector3d::Zero(), Eigen::Vector3d::Zero());
  EXPECT_GT(box.basePose().translation().x() - x0, 0.1);
  // reset_world
  sleep();
  box.resetToSpawn();
  EXPECT_FALSE(box.asleep());
}

TEST(Sleeping, OnlyJointlessModelsThatAllowItSleep) {
  // <allow_auto_disable>false</allow_auto_disable>, or any joint (Gazebo's rule): never.
  std::string no_sleep = boxModel("a", Eigen::Vector3d(0.2, 0.2, 0.2), 1.0, "0 0 0.1 0 0 0");
  no_sleep.insert(no_sleep.find("<link"), "<allow_auto_disable>false</allow_auto_disable>");
  const std::string jointed =
      "<model name='b'><pose>1 0 0.1 0 0 0</pose><link name='l1'><inertial><mass>1</mass>"
      "<inertia><ixx>0.01</ixx><iyy>0.01</iyy><izz>0.01</izz></inertia></inertial>"
      "<collision name='c'><geometry><box><size>0.2 0.2 0.2</size></box></geometry></collision>"
      "</link><link name='l2'><pose>0 0 0.2 0 0 0</pose><inertial><mass>1</mass><inertia><ixx>0.01"
      "</ixx><iyy>0.01</iyy><izz>0.01</izz></inertia></inertial><collision name='c'><geometry><box>"
      "<size>0.2 0.2 0.2</size></box></geometry></collision></link><joint name='j' type='fixed'>"
      "<parent>l1</parent><child>l2</child></joint></model>";
  FreeWorld w(no_sleep + jointed + boxModel("c", Eigen::Vector3d(0.2, 0.2, 0.2), 1.0, "2 0 0.1 0 0 0"));
  for (int k = 0; k < 3000; ++k) w.physics.step();
  EXPECT_FALSE(w.physics.freeBody(w.physics.freeBodyIndex("a")).asleep());
  EXPECT_FALSE(w.physics.freeBody(w.physics.freeBodyIndex("b")).asleep());
  EXPECT_TRUE(w.physics.freeBody(w.physics.freeBodyIndex("c")).asleep());
  // sleep_time 0: nothing sleeps.
  PhysicsOptions o = physicsOptionsFor(w.desc);
  o.sleep_time = 0.0;
  PhysicsWorld never(o);
  addWorldToPhysics(w.desc, &never, {});
  for (int k = 0; k < 3000; ++k) never.step();
  EXPECT_FALSE(never.freeBody(never.freeBodyIndex("c")).asleep());
}

}  // namespace
}  // namespace tianracer_sim
