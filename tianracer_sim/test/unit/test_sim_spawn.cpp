// Models added and removed at run time (spawn_sdf_model, spawn_urdf_model, delete_model):
// a spawned box falls and rests, removed bodies and static shapes leave the physics and the
// scene, a removed robot's name can be spawned again, and bad SDF is an error naming it.
#include <gtest/gtest.h>

#include <string>
#include <vector>

#include "sim_test_support.h"
#include "tianracer_sim/sim/robot_scene.h"
#include "tianracer_sim/sim/simulation.h"
#include "tianracer_sim/sim/world_physics.h"
#include "tianracer_sim/world/world.h"

namespace tianracer_sim {
namespace {

/// spawn_sdf_model's string: a box of edge `a` (m), mass 1 kg, static or not, at z.
std::string boxSdf(const std::string& name, double a, bool is_static, double z) {
  const std::string s = std::to_string(a);
  const double i = a * a / 6.0;
  return "<?xml version='1.0'?><sdf version='1.6'><model name='" + name + "'><static>" +
         (is_static ? "true" : "false") + "</static><pose>0 0 " + std::to_string(z) +
         " 0 0 0</pose><link name='link'><inertial><mass>1</mass><inertia><ixx>" +
         std::to_string(i) + "</ixx><iyy>" + std::to_string(i) + "</iyy><izz>" +
         std::to_string(i) + "</izz></inertia></inertial><collision name='c'><geometry><box><size>" +
         s + " " + s + " " + s + "</size></box></geometry></collision><visual name='v'><geometry>"
         "<box><size>" + s + " " + s + " " + s + "</size></box></geometry></visual></link></model></sdf>";
}

struct SpawnWorld {
  WorldDescription desc = test::groundWorld();
  Simulation sim{physicsOptionsFor(desc)};
  Scene scene;
  SpawnWorld() {
    addWorldToPhysics(desc, &sim.physics(), WarningSink());
    addToScene(desc, scene);
  }
  /// What the node does for spawn_sdf_model: parse, add to the world description, physics
  /// and scene.
  WorldModelBodies spawn(const std::string& sdf) {
    desc.models.push_back(loadModelString(sdf, "spawn_sdf_model", "."));
    WorldDescription one;
    one.models.push_back(desc.models.back());
    addToScene(one, scene);
    return addModelToPhysics(desc, desc.models.back(), &sim.physics(), WarningSink());
  }
  void run(double seconds) {
    for (int k = 0; k < static_cast<int>(seconds / sim.dt()); ++k) sim.step();
  }
};

TEST(Spawn, SpawnedBoxFallsAndRestsOnTheGround) {
  SpawnWorld w;
  const WorldModelBodies box = w.spawn(boxSdf("crate", 0.2, false, 1.0));
  ASSERT_GE(box.free_body, 0);
  const PhysicsRobot& body = w.sim.physics().freeBody(box.free_body);
  w.run(2.0);
  EXPECT_NEAR(body.basePose().translation().z(), 0.1, 2e-3);
  EXPECT_LT(body.baseTwist().linear.norm(), 1e-3);
  // The sensors' scene got its body and shapes.
  int items = 0;
  for (const SceneItem& item : w.scene.items) items += w.scene.bodies[item.body].model == "crate";
  EXPECT_EQ(items, 2);  // collision + visual
}

TEST(Spawn, RemovedStaticShapeNoLongerHoldsWhatRestedOnIt) {
  SpawnWorld w;
  const WorldModelBodies table = w.spawn(boxSdf("table", 1.0, true, 0.5));  // top at z 1
  ASSERT_EQ(table.statics.size(), 1u);
  const WorldModelBodies box = w.spawn(boxSdf("crate", 0.2, false, 1.3));
  const PhysicsRobot& body = w.sim.physics().freeBody(box.free_body);
  w.run(1.5);
  EXPECT_NEAR(body.basePose().translation().z(), 1.1, 2e-3);
  removeModelFromPhysics(table, &w.sim.physics());
  removeModelFromScene("table", &w.scene);
  w.run(1.5);
  EXPECT_NEAR(body.basePose().translation().z(), 0.1, 2e-3);
  for (const SceneItem& item : w.scene.items) EXPECT_NE(w.scene.bodies[item.body].model, "table");
}

TEST(Spawn, RemovedFreeBodyLeavesTheWorldAndTheOthersKeepTheirIndex) {
  SpawnWorld w;
  const WorldModelBodies a = w.spawn(boxSdf("a", 0.2, false, 0.5));
  const WorldModelBodies b = w.spawn(boxSdf("b", 0.2, false, 2.0));
  removeModelFromPhysics(a, &w.sim.physics());
  EXPECT_FALSE(w.sim.physics().hasFreeBody(a.free_body));
  EXPECT_EQ(w.sim.physics().freeBodyIndex("a"), -1);
  EXPECT_EQ(w.sim.physics().freeBodyIndex("b"), b.free_body);
  EXPECT_THROW(w.sim.physics().freeBody(a.free_body), PhysicsError);
  w.run(2.0);
  w.sim.resetWorld();  // skips the removed body
  EXPECT_NEAR(w.sim.physics().freeBody(b.free_body).basePose().translation().z(), 2.0, 1e-9);
  // Its name is free again.
  const WorldModelBodies again = w.spawn(boxSdf("a", 0.2, false, 0.5));
  EXPECT_EQ(w.sim.physics().freeBodyIndex("a"), again.free_body);
}

TEST(Spawn, RemovedRobotLeavesThePhysicsAndItsNameCanBeSpawnedAgain) {
  SpawnWorld w;
  auto add = [&](const std::string& name, double y) -> SimRobot& {
    RobotConfig config = test::tianracerAt(Eigen::Vector3d(0.0, y, test::kSpawnZ), name);
    config.controllers = test::shippedControllers();
    return w.sim.addRobot(std::move(config));
  };
  const RobotId first = add("car1", -0.5).id;
  const RobotId second = add("car2", 0.5).id;
  w.run(0.2);
  w.sim.removeRobot("car2");
  EXPECT_EQ(w.sim.findRobot("car2"), nullptr);
  EXPECT_FALSE(w.sim.physics().hasRobot(second));
  EXPECT_EQ(w.sim.physics().robotId("car2"), -1);
  EXPECT_THROW(w.sim.removeRobot("car2"), ModelError);
  w.run(0.2);
  EXPECT_TRUE(w.sim.physics().robot(first).basePose().matrix().allFinite());
  const SimRobot& again = add("car2", 0.5);
  EXPECT_NE(again.id, second);
  EXPECT_EQ(w.sim.physics().robotId("car2"), again.id);
  w.run(0.5);
  // Resting on its wheels again, where it was spawned.
  EXPECT_NEAR(w.sim.physics().robot(again.id).basePose().translation().y(), 0.5, 1e-3);
}

TEST(Spawn, MalformedSdfIsAnErrorNamingTheSource) {
  try {
    loadModelString("<sdf version='1.6'><model name='x'><link name='l'>", "spawn_sdf_model 'x'",
                    ".");
    FAIL() << "no error";
  } catch (const WorldError& e) {
    EXPECT_NE(std::string(e.what()).find("spawn_sdf_model 'x'"), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("malformed XML"), std::string::npos) << e.what();
  }
  EXPECT_THROW(loadModelString("<sdf version='1.6'><world name='w'/></sdf>", "s", "."), WorldError);
}

}  // namespace
}  // namespace tianracer_sim
