// A world's <actor> in the Simulator (docs/actors.md): listed among the models with the pose its
// script gives at the sim time, its link where the lidar and the scene see it, found by the
// state services' name resolver, and not movable by set_model_state. Sim time only.
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

#include "tianracer_sim/lidar/ray_caster.h"
#include "tianracer_sim/simulator/simulator.h"
#include "tianracer_sim/world/world.h"

namespace tianracer_sim {
namespace {

using ::testing::HasSubstr;

WorldDescription actorWorld(const std::string& extra = "", const std::string& surface = "") {
  // The walker goes from y = -2 to y = 2 along x = 3 in 4 s, then stops (loop false).
  return loadWorldString(
      std::string("<sdf version='1.6'><world name='w'>") +
      "<include><uri>model://ground_plane</uri></include>"
      "<actor name='walker'><pose>0 9 0 0 0 0</pose>"
      "<link name='body'><pose>0 0 1 0 0 0</pose><collision name='c'><geometry><box>"
      "<size>0.4 0.4 2</size></box></geometry>" + surface + "</collision><visual name='v'><geometry><box>"
      "<size>0.4 0.4 2</size></box></geometry></visual></link>"
      "<script><loop>false</loop><trajectory id='0' type='walk'>"
      "<waypoint><time>0</time><pose>3 -2 0 0 0 0</pose></waypoint>"
      "<waypoint><time>4</time><pose>3 2 0 0 0 0</pose></waypoint>"
      "</trajectory></script></actor>" +
          extra + "</world></sdf>",
      "actor.world", ".");
}

TEST(SimulatorActor, ListedWithItsScriptedPoseAndSeenByTheLidar) {
  Simulator sim(actorWorld(), {});
  const ModelId id = sim.findModel("walker");
  ASSERT_NE(id, kNoModel);
  const std::vector<ModelId> ids = sim.modelIds();
  EXPECT_NE(std::find(ids.begin(), ids.end(), id), ids.end());
  EXPECT_EQ(sim.physicsOf(id), nullptr);  // kinematic: no physics body
  // Before its first frame (1/30 s) it stands at its <pose>.
  sim.step(10);
  EXPECT_NEAR((sim.modelState(id).X_WE.translation() - Eigen::Vector3d(0, 9, 0)).norm(), 0, 1e-12);
  const WorldDescription& w = sim.world();
  ASSERT_EQ(w.actors.size(), 1u);
  RayCaster caster;
  const std::vector<Eigen::Vector3f> dir{Eigen::Vector3f(1, 0, 0)};
  auto range = [&]() {
    caster.update(sim.scene());
    float d = 0;
    caster.castRays(Eigen::Vector3d(0, 0, 1), dir, 0.0f, 10.0f, &d);
    return d;
  };
  sim.step(490);  // t = 0.5: y near -1.8, off the ray
  const double y0 = sim.modelState(id).X_WE.translation().y();
  EXPECT_LT(y0, -1.5);
  EXPECT_TRUE(std::isinf(range()));
  sim.step(1500);  // t = 2.0: last frame 1.972 s, y within the box's half width of 0
  const Eigen::Isometry3d X = sim.modelState(id).X_WE;
  EXPECT_NEAR(X.translation().x(), 3.0, 1e-12);
  EXPECT_LT(std::abs(X.translation().y()), 0.2);
  EXPECT_NEAR(range(), 2.8f, 1e-4);  // the box's near face
  // The link is 1 m above the actor's frame.
  EXPECT_NEAR((sim.linkPose({id, "body"}).translation() - X.translation()).z(), 1.0, 1e-12);
  sim.step(3000);  // t = 5: stopped at its last frame (3.978 s), y near 2
  EXPECT_GT(sim.modelState(id).X_WE.translation().y(), 1.9);
  EXPECT_TRUE(std::isinf(range()));
}

TEST(SimulatorActor, TheStateServicesFindItAndCannotMoveIt) {
  Simulator sim(actorWorld(), {});
  sim.step(2000);
  const Entities entities = sim.entities();
  const std::vector<std::string> names = entities.modelNames();
  EXPECT_NE(std::find(names.begin(), names.end(), "walker"), names.end());
  const Entity e = entities.find("walker", true);
  EXPECT_TRUE(e.actor);
  const EntityState s = entities.state(e);
  EXPECT_NEAR(s.X_WE.translation().x(), 3.0, 1e-12);
  EXPECT_EQ(s.V_WE.linear.norm(), 0.0);  // as Gazebo's SetWorldPose leaves it
  EXPECT_NEAR(entities.state(entities.find("walker::body", false)).X_WE.translation().z(), 1.0,
              1e-12);
  try {
    entities.setBase(e, EntityState{}, false);
    FAIL() << "an actor was moved";
  } catch (const InputError& err) {
    EXPECT_THAT(err.what(), HasSubstr("is an actor"));
  }
}

TEST(SimulatorActor, ItsCollisionsPushWhatTheyMeetAndNothingPushesIt) {
  // Gazebo's actor is a static model its script moves (teleported at 30 Hz, no velocity): a free
  // box in its way is pushed out of it no faster than the contacts' max_vel (the smaller of the
  // two surfaces', SDF default 0.01 m/s), as ODE's contact correction is capped.
  const std::string fast = "<surface><contact><ode><max_vel>100</max_vel></ode></contact></surface>";
  auto boxModel = [](const std::string& surface) {
    return "<model name='box'><pose>3 0 0.15 0 0 0</pose><link name='l'><inertial><mass>1</mass>"
           "<inertia><ixx>0.01</ixx><iyy>0.01</iyy><izz>0.01</izz></inertia></inertial>"
           "<collision name='c'><geometry><box><size>0.3 0.3 0.3</size></box></geometry>" +
           surface + "</collision></link></model>";
  };
  {
    Simulator sim(actorWorld(boxModel(fast), fast), {});
    const ModelId box = sim.findModel("box");
    const ModelId walker = sim.findModel("walker");
    sim.step(1000);  // t = 1: the walker (y about -1.2) has not reached the box
    EXPECT_NEAR(sim.modelState(box).X_WE.translation().y(), 0.0, 1e-3);
    sim.step(2500);  // t = 3.5: the walker is past y = 1, the box went ahead of it
    const double walker_y = sim.modelState(walker).X_WE.translation().y();
    const double box_y = std::abs(sim.modelState(box).X_WE.translation().y());
    EXPECT_GT(walker_y, 1.0);
    EXPECT_GT(box_y, 0.5) << "the box was not pushed";
    // The walker is exactly where its script says (nothing pushed it back).
    EXPECT_NEAR(sim.modelState(walker).X_WE.translation().x(), 3.0, 1e-12);
  }
  {
    // SDF's default max_vel 0.01 m/s: the walker (1 m/s) passes through, the box creeps.
    Simulator sim(actorWorld(boxModel("")), {});
    sim.step(3500);
    const Eigen::Vector3d p = sim.modelState(sim.findModel("box")).X_WE.translation();
    EXPECT_GT((p - Eigen::Vector3d(3, 0, 0.15)).norm(), 0.002);
    EXPECT_LT((p - Eigen::Vector3d(3, 0, 0.15)).norm(), 0.05);
  }
}

TEST(SimulatorActor, DeletedItIsGoneFromStatesSceneAndPhysics) {
  const std::string box =
      "<model name='box'><pose>3 0 0.15 0 0 0</pose><link name='l'><inertial><mass>1</mass>"
      "<inertia><ixx>0.01</ixx><iyy>0.01</iyy><izz>0.01</izz></inertia></inertial>"
      "<collision name='c'><geometry><box><size>0.3 0.3 0.3</size></box></geometry><surface>"
      "<contact><ode><max_vel>100</max_vel></ode></contact></surface></collision></link></model>";
  Simulator sim(actorWorld(box, "<surface><contact><ode><max_vel>100</max_vel></ode></contact>"
                                "</surface>"),
                {});
  sim.step(500);
  sim.removeModel("walker");
  EXPECT_EQ(sim.findModel("walker"), kNoModel);
  const std::vector<std::string> names = sim.entities().modelNames();
  EXPECT_EQ(std::find(names.begin(), names.end(), "walker"), names.end());
  sim.step(3000);  // it would have pushed the box by now
  EXPECT_NEAR(sim.modelState(sim.findModel("box")).X_WE.translation().y(), 0.0, 1e-3);
  for (const SceneBody& b : sim.scene().bodies) EXPECT_NE(b.model, "walker");
}

}  // namespace
}  // namespace tianracer_sim
