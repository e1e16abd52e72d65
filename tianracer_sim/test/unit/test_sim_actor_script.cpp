// <actor> scripts as Gazebo 11 plays them (docs/actors.md): the pose interpolation against
// Gazebo's formulas computed here by hand, the 30 Hz frames, loop, delay_start, auto_start, id
// order, the lidar seeing a passing actor, and every broken form an error at its line with the
// rest of the world loading. Sim time only.
#include <gtest/gtest.h>

#include <cmath>
#include <string>
#include <vector>

#include "tianracer_sim/lidar/ray_caster.h"
#include "tianracer_sim/world/actor.h"
#include "tianracer_sim/world/world.h"

namespace tianracer_sim {
namespace {

constexpr double kPi = 3.14159265358979323846;

std::string worldWith(const std::string& script, const std::string& extra = "") {
  return std::string(
             "<sdf version='1.6'><world name='w'>\n"  // line 1
             "<model name='wall'><static>true</static><link name='l'><collision name='c'>\n"
             "<geometry><box><size>1 1 1</size></box></geometry></collision></link></model>\n"
             "<actor name='walker'>\n"                                        // line 4
             "<pose>5 5 0 0 0 0</pose>\n"                                      // line 5
             "<link name='body'><pose>0 0 1 0 0 0</pose><collision name='c'>\n"  // line 6
             "<geometry><box><size>0.4 0.4 2</size></box></geometry></collision></link>\n"
             "<skin><filename>walk.dae</filename></skin>\n"                   // line 8
             "<script>\n") +                                                   // line 9
         script + "</script></actor>\n" + extra + "</world></sdf>\n";
}

const char* kThreeWaypoints =
    "<trajectory id='0' type='walk'>\n"                                  // line 10
    "<waypoint><time>0</time><pose>0 0 0 0 0 0</pose></waypoint>\n"      // 11
    "<waypoint><time>1</time><pose>1 0 0 0 0 1.5707963267948966</pose></waypoint>\n"
    "<waypoint><time>2</time><pose>1 1 0 0 0 1.5707963267948966</pose></waypoint>\n"
    "</trajectory>\n";

struct Loaded {
  WorldDescription world;
  std::vector<std::string> warnings, errors;
};

Loaded load(const std::string& xml, bool strict = false) {
  Loaded out;
  WorldLoadOptions o;
  o.warn = [&out](const std::string& m) { out.warnings.push_back(m); };
  o.error = [&out](const std::string& m) { out.errors.push_back(m); };
  o.strict = strict;
  out.world = loadWorldString(xml, "w.world", ".", o);
  return out;
}

double yawOf(const Eigen::Isometry3d& X) {
  return std::atan2(X.linear()(1, 0), X.linear()(0, 0));
}

// Cubic Hermite with Catmull-Rom tangents times (1 - tension), ends one-sided (ignition's
// Spline::RecalcTangents / Interpolate), written out for the three points above.
Eigen::Vector3d hermite(double s, double tension) {
  const Eigen::Vector3d p0(0, 0, 0), p1(1, 0, 0), p2(1, 1, 0);
  const double f = 0.5 * (1 - tension);
  const Eigen::Vector3d m0 = f * (p1 - p0), m1 = f * (p2 - p0);
  const double s2 = s * s, s3 = s2 * s;
  return (2 * s3 - 3 * s2 + 1) * p0 + (s3 - 2 * s2 + s) * m0 + (-2 * s3 + 3 * s2) * p1 +
         (s3 - s2) * m1;
}

TEST(ActorScript, ParsesTheScriptAndNamesTheSkinAsNotSimulated) {
  const Loaded l = load(worldWith("<loop>false</loop><delay_start>0.5</delay_start>"
                                  "<auto_start>true</auto_start>" +
                                  std::string(kThreeWaypoints)));
  EXPECT_TRUE(l.errors.empty());
  ASSERT_EQ(l.world.actors.size(), 1u);
  const ActorDescription& a = l.world.actors[0];
  EXPECT_EQ(a.model.name, "walker");
  EXPECT_FALSE(a.script.loop);
  EXPECT_DOUBLE_EQ(a.script.delay_start, 0.5);
  ASSERT_EQ(a.script.trajectories.size(), 1u);
  EXPECT_EQ(a.script.trajectories[0].waypoints.size(), 3u);
  ASSERT_EQ(a.model.links.size(), 1u);
  bool skin = false;
  for (const std::string& w : l.warnings)
    skin |= w.find("w.world:8: <skin> in <actor> is not simulated") != std::string::npos;
  EXPECT_TRUE(skin) << "the skin is named as left out, with its line";
  // addToScene makes the actor's link a moving body.
  Scene scene;
  const auto bodies = addToScene(l.world, scene);
  ASSERT_TRUE(bodies.count("walker::body"));
  EXPECT_FALSE(scene.bodies[bodies.at("walker::body")].is_static);
}

TEST(ActorScript, PositionIsGazebosSplineWithTheTrajectorysTension) {
  for (const double tension : {0.0, 0.5, 1.0}) {
    const Loaded l = load(worldWith(
        "<trajectory id='0' type='walk' tension='" + std::to_string(tension) +
        "'>\n<waypoint><time>0</time><pose>0 0 0 0 0 0</pose></waypoint>\n"
        "<waypoint><time>1</time><pose>1 0 0 0 0 0</pose></waypoint>\n"
        "<waypoint><time>2</time><pose>1 1 0 0 0 0</pose></waypoint>\n</trajectory>\n"));
    const ActorTrajectory& tr = l.world.actors.at(0).script.trajectories.at(0);
    for (const double s : {0.1, 0.25, 0.5, 0.9}) {
      const Eigen::Vector3d p = trajectoryPose(tr, s).translation();
      EXPECT_NEAR((p - hermite(s, tension)).norm(), 0.0, 1e-12) << tension << " " << s;
    }
  }
  // The hand-computed midpoint of the first segment, tension 0: (0.5, -0.0625, 0).
  const Loaded l = load(worldWith(kThreeWaypoints));
  const Eigen::Vector3d mid = trajectoryPose(l.world.actors[0].script.trajectories[0], 0.5)
                                  .translation();
  EXPECT_NEAR(mid.x(), 0.5, 1e-12);
  EXPECT_NEAR(mid.y(), -0.0625, 1e-12);
  // On the waypoints exactly.
  EXPECT_NEAR((trajectoryPose(l.world.actors[0].script.trajectories[0], 2.0).translation() -
               Eigen::Vector3d(1, 1, 0)).norm(), 0.0, 1e-12);
}

TEST(ActorScript, RotationIsSquadWithShoemakesTangents) {
  // Two waypoints, yaw 0 -> theta: tangents yaw(-theta/4), yaw(5 theta/4); squad at s = 0.25 is
  // slerp(0.375, yaw(theta/4), yaw(theta/8)) = yaw(0.203125 theta); at 0.5 it is theta/2.
  const double theta = kPi / 2;
  const Loaded l = load(worldWith(
      "<trajectory id='0' type='turn'>\n<waypoint><time>0</time><pose>0 0 0 0 0 0</pose>"
      "</waypoint>\n<waypoint><time>4</time><pose>0 0 0 0 0 1.5707963267948966</pose>"
      "</waypoint>\n</trajectory>\n"));
  const ActorTrajectory& tr = l.world.actors.at(0).script.trajectories.at(0);
  EXPECT_NEAR(yawOf(trajectoryPose(tr, 1.0)), 0.203125 * theta, 1e-9);
  EXPECT_NEAR(yawOf(trajectoryPose(tr, 2.0)), 0.5 * theta, 1e-9);
  EXPECT_NEAR(yawOf(trajectoryPose(tr, 3.0)), theta - 0.203125 * theta, 1e-9);
}

TEST(ActorScript, FramesAt30HzOfSimTimeAndTheActorsPoseUntilTheFirst) {
  const Loaded l = load(worldWith(kThreeWaypoints));
  const ActorDescription& a = l.world.actors.at(0);
  const ActorTrajectory& tr = a.script.trajectories.at(0);
  ActorPlayer player(a.script, a.model.X_WM, 0.001);
  // Until the first frame (sim time >= 1/30 s since load: step 34), the actor's <pose>.
  EXPECT_NEAR((player.poseAt(0.033).translation() - Eigen::Vector3d(5, 5, 0)).norm(), 0, 1e-12);
  EXPECT_NEAR((player.poseAt(0.034).translation() - trajectoryPose(tr, 0.034).translation())
                  .norm(), 0, 1e-12);
  // Frames every 34 steps: at t = 0.5 the last frame was 0.476 (14 x 0.034).
  const Eigen::Isometry3d X = player.poseAt(0.5);
  EXPECT_NEAR((X.translation() - hermite(0.476, 0.0)).norm(), 0.0, 1e-9);
  EXPECT_NEAR((player.poseAt(0.509).translation() - hermite(0.476, 0.0)).norm(), 0.0, 1e-9);
  EXPECT_NEAR((player.poseAt(0.510).translation() - hermite(0.510, 0.0)).norm(), 0.0, 1e-9);
}

TEST(ActorScript, LoopRestartsAfterTheScriptAndNoLoopStopsAtTheLastFrame) {
  {
    const Loaded l = load(worldWith(kThreeWaypoints));  // loop defaults to true
    const ActorDescription& a = l.world.actors.at(0);
    ActorPlayer player(a.script, a.model.X_WM, 0.001);
    EXPECT_DOUBLE_EQ(player.scriptLength(), 2.0);
    // Frame 59 at 2.006 s: script time 0.006 into the second round.
    const Eigen::Isometry3d X = player.poseAt(2.010);
    EXPECT_NEAR((X.translation() - trajectoryPose(a.script.trajectories[0], 0.006).translation())
                    .norm(), 0.0, 1e-9);
    EXPECT_TRUE(player.active());
    EXPECT_NEAR(X.translation().x(), 0.0, 0.01);  // back at the start
  }
  {
    const Loaded l = load(worldWith("<loop>false</loop>" + std::string(kThreeWaypoints)));
    const ActorDescription& a = l.world.actors.at(0);
    ActorPlayer player(a.script, a.model.X_WM, 0.001);
    const Eigen::Isometry3d X = player.poseAt(5.0);
    EXPECT_FALSE(player.active());
    // It stays at the last frame before the end: 58 x 0.034 = 1.972 s.
    EXPECT_NEAR((X.translation() - trajectoryPose(a.script.trajectories[0], 1.972).translation())
                    .norm(), 0.0, 1e-9);
  }
}

TEST(ActorScript, DelayStartHoldsThePoseThenPlaysFromZero) {
  const Loaded l = load(worldWith("<delay_start>1.0</delay_start>" +
                                  std::string(kThreeWaypoints)));
  const ActorDescription& a = l.world.actors.at(0);
  ActorPlayer player(a.script, a.model.X_WM, 0.001);
  EXPECT_NEAR((player.poseAt(0.999).translation() - Eigen::Vector3d(5, 5, 0)).norm(), 0, 1e-12);
  EXPECT_NEAR(player.poseAt(1.0).translation().norm(), 0.0, 1e-12);  // script time 0
  EXPECT_NEAR((player.poseAt(1.5).translation() - hermite(0.476, 0.0)).norm(), 0.0, 1e-9);
  // A world reset (time going back) plays it from the start again.
  EXPECT_NEAR((player.poseAt(0.5).translation() - Eigen::Vector3d(5, 5, 0)).norm(), 0, 1e-12);
}

TEST(ActorScript, AutoStartFalseWaitsForPlay) {
  const Loaded l = load(worldWith("<auto_start>false</auto_start>" +
                                  std::string(kThreeWaypoints)));
  const ActorDescription& a = l.world.actors.at(0);
  ActorPlayer player(a.script, a.model.X_WM, 0.001);
  EXPECT_NEAR((player.poseAt(10.0).translation() - Eigen::Vector3d(5, 5, 0)).norm(), 0, 1e-12);
  player.play();  // at 10 s
  // No frame since load, so the first is at the next step (10.001 s, script time 0.001), then
  // every 34 steps: at 10.5 the last was 10.477, script time 0.477.
  EXPECT_NEAR((player.poseAt(10.001).translation() - hermite(0.001, 0.0)).norm(), 0.0, 1e-9);
  EXPECT_NEAR((player.poseAt(10.5).translation() - hermite(0.477, 0.0)).norm(), 0.0, 1e-9);
}

TEST(ActorScript, TrajectoriesPlayInIdOrderWaypointsInTimeOrder) {
  const Loaded l = load(worldWith(
      "<trajectory id='7' type='b'>\n"
      "<waypoint><time>1</time><pose>9 0 0 0 0 0</pose></waypoint>\n"
      "<waypoint><time>0</time><pose>8 0 0 0 0 0</pose></waypoint>\n</trajectory>\n"
      "<trajectory id='3' type='a'>\n"
      "<waypoint><time>0.5</time><pose>1 0 0 0 0 0</pose></waypoint>\n</trajectory>\n"));
  const ActorScript& s = l.world.actors.at(0).script;
  ASSERT_EQ(s.trajectories.size(), 2u);
  EXPECT_EQ(s.trajectories[0].id, 3);
  EXPECT_EQ(s.trajectories[1].id, 7);
  EXPECT_DOUBLE_EQ(s.trajectories[1].waypoints[0].time, 0.0);
  ActorPlayer player(s, l.world.actors[0].model.X_WM, 0.001);
  // Trajectory 3: one waypoint, held for its 0.5 s; then trajectory 7 from x = 8 to 9.
  EXPECT_NEAR(player.poseAt(0.3).translation().x(), 1.0, 1e-12);
  EXPECT_NEAR(player.poseAt(0.476).translation().x(), 1.0, 1e-12);  // frame at 0.476
  // The frame at 0.510 s is 0.01 s into trajectory 7: s = 0.01 of its one segment.
  const double s1 = 0.01, m = 0.5;  // one-sided end tangents (9 - 8) / 2
  EXPECT_NEAR(player.poseAt(0.51).translation().x(),
              8.0 + (-2 * s1 * s1 * s1 + 3 * s1 * s1) +
                  m * (s1 * s1 * s1 - 2 * s1 * s1 + s1) + m * (s1 * s1 * s1 - s1 * s1),
              1e-12);
  EXPECT_GT(player.poseAt(1.2).translation().x(), 8.5);
}

TEST(ActorScript, TheLidarSeesTheActorWhereItsScriptPutsIt) {
  // The actor walks along y through x = 3 in front of a lidar at the origin looking along +x.
  const Loaded l = load(worldWith(
      "<trajectory id='0' type='walk'>\n"
      "<waypoint><time>0</time><pose>3 -2 0 0 0 0</pose></waypoint>\n"
      "<waypoint><time>4</time><pose>3 2 0 0 0 0</pose></waypoint>\n</trajectory>\n"));
  Scene scene;
  addToScene(l.world, scene);
  std::vector<ActorPlayer> players = actorPlayers(l.world, 0.001);
  RayCaster caster;
  const std::vector<Eigen::Vector3f> dir{Eigen::Vector3f(1, 0, 0)};
  const Eigen::Vector3d origin(0, 0, 1);
  auto rangeAt = [&](double t) {
    updateActorScene(l.world, &players, t, &scene);
    caster.update(scene);
    float d = 0;
    caster.castRays(origin, dir, 0.0f, 10.0f, &d);
    return d;
  };
  EXPECT_TRUE(std::isinf(rangeAt(0.5)));  // at y < -0.2: the ray passes
  // At t = 2.0 the last frame was 1.972 s (58 x 0.034): y = -2 + 4 * 1.972 / 4 ... the spline of
  // two points with one-sided tangents is not linear, but the box (0.4 wide) is on the ray.
  const double y = players[0].poseAt(2.0).translation().y();
  ASSERT_LT(std::abs(y), 0.2);
  EXPECT_NEAR(rangeAt(2.0), 3.0 - 0.2, 1e-4);  // the box's near face
  EXPECT_TRUE(std::isinf(rangeAt(3.9)));
}

struct BadCase {
  const char* name;
  std::string script;
  std::string expect;  // in the error
};

TEST(ActorScript, EachBrokenFormIsAnErrorAtItsLineAndTheRestLoads) {
  const std::vector<BadCase> cases = {
      {"no waypoints", "<trajectory id='0' type='w'>\n</trajectory>\n",
       "w.world:10: actor 'walker' <trajectory id='0'> has no <waypoint>"},
      {"nan time",
       "<trajectory id='0' type='w'>\n<waypoint><time>nan</time><pose>0 0 0 0 0 0</pose>"
       "</waypoint>\n</trajectory>\n",
       "w.world:11:"},
      {"negative time",
       "<trajectory id='0' type='w'>\n<waypoint><time>-1</time><pose>0 0 0 0 0 0</pose>"
       "</waypoint>\n</trajectory>\n",
       "w.world:11: actor 'walker' <trajectory id='0'>: <waypoint> <time> -1 is negative"},
      {"duplicate time",
       "<trajectory id='0' type='w'>\n<waypoint><time>1</time><pose>0 0 0 0 0 0</pose>"
       "</waypoint>\n<waypoint><time>1</time><pose>1 0 0 0 0 0</pose></waypoint>\n"
       "</trajectory>\n",
       "w.world:12: actor 'walker' <trajectory id='0'>: <waypoint> <time> 1 is the time of the "
       "waypoint at line 11"},
      {"inf pose",
       "<trajectory id='0' type='w'>\n<waypoint><time>0</time><pose>inf 0 0 0 0 0</pose>"
       "</waypoint>\n</trajectory>\n",
       "w.world:11:"},
      {"short pose",
       "<trajectory id='0' type='w'>\n<waypoint><time>0</time><pose>0 0 0</pose>"
       "</waypoint>\n</trajectory>\n",
       "'0 0 0' is not 6 numbers"},
      {"no time",
       "<trajectory id='0' type='w'>\n<waypoint><pose>0 0 0 0 0 0</pose></waypoint>\n"
       "</trajectory>\n",
       "w.world:11:"},
      {"bad id", "<trajectory id='x1' type='w'>\n<waypoint><time>0</time>"
                 "<pose>0 0 0 0 0 0</pose></waypoint>\n</trajectory>\n",
       "w.world:10: actor 'walker': <trajectory> id 'x1' is not an integer"},
      {"bad tension", "<trajectory id='0' type='w' tension='nan'>\n<waypoint><time>0</time>"
                      "<pose>0 0 0 0 0 0</pose></waypoint>\n</trajectory>\n",
       "w.world:10: actor 'walker': <trajectory> tension 'nan' is not a finite number"},
      {"bad loop", "<loop>sometimes</loop>\n" + std::string(kThreeWaypoints), "sometimes"},
      {"nan delay", "<delay_start>nan</delay_start>\n" + std::string(kThreeWaypoints), "nan"},
  };
  for (const BadCase& c : cases) {
    const Loaded l = load(worldWith(c.script));
    ASSERT_EQ(l.errors.size(), 1u) << c.name;
    RecordProperty(c.name, l.errors[0]);  // docs/bad_input.md copies these (--gtest_output=xml)
    EXPECT_NE(l.errors[0].find(c.expect), std::string::npos) << c.name << ": " << l.errors[0];
    EXPECT_NE(l.errors[0].find("the actor is left out"), std::string::npos) << c.name;
    EXPECT_TRUE(l.world.actors.empty()) << c.name;
    ASSERT_EQ(l.world.models.size(), 1u) << c.name << ": the rest of the world loads";
    EXPECT_THROW(load(worldWith(c.script), true), WorldError) << c.name << " (strict)";
  }
}

TEST(ActorScript, AnActorNamedLikeAModelIsLeftOut) {
  const Loaded l = load(worldWith(kThreeWaypoints,
                                  "<actor name='wall'><script>" + std::string(kThreeWaypoints) +
                                      "</script></actor>\n"));
  ASSERT_EQ(l.errors.size(), 1u);
  EXPECT_NE(l.errors[0].find("duplicate model name 'wall'"), std::string::npos) << l.errors[0];
  EXPECT_NE(l.errors[0].find("the actor is left out"), std::string::npos) << l.errors[0];
  EXPECT_EQ(l.world.actors.size(), 1u);
}

}  // namespace
}  // namespace tianracer_sim
