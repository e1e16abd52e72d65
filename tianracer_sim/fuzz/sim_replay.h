// The promises of the simulation, checked on one robot or world: the fuzz harness (fuzz_sim.cpp)
// and the replay of the regression corpus (test/unit/test_sim_fuzz_regressions.cpp) build,
// step and cast the same way, so that CI, which has no libFuzzer, replays what the fuzzer
// found. Header-only.
//
// What loads is stepped `steps` times on a ground plane (a robot) or in its own world, with a
// fan of rays cast every `cast_every` steps: every body's pose and every joint's position and
// velocity stay finite, and no ray distance is NaN (+inf: no hit). Loading and building may
// only end in InputError or PhysicsError, which the caller catches.
#ifndef TIANRACER_SIM_FUZZ_SIM_REPLAY_H
#define TIANRACER_SIM_FUZZ_SIM_REPLAY_H

#include <cmath>
#include <string>
#include <vector>

#include "tianracer_sim/lidar/ray_caster.h"
#include "tianracer_sim/scene/scene.h"
#include "tianracer_sim/sim/robot_scene.h"
#include "tianracer_sim/sim/simulation.h"
#include "tianracer_sim/sim/world_physics.h"
#include "tianracer_sim/world/world.h"

namespace tianracer_sim_fuzz {

struct SimReplay {
  int steps = 300;
  int cast_every = 50;
  int rays = 36;  // a fan around the z axis, 5 % down, from (-1, 0, 0.3)
};

/// What broke in `r`'s state ("" when nothing).
inline std::string brokenBodyPromise(const tianracer_sim::PhysicsRobot& r) {
  if (!r.basePose().matrix().allFinite()) return "base pose not finite";
  for (std::size_t j = 0; j < r.joints().size(); ++j) {
    if (!std::isfinite(r.jointPosition(static_cast<int>(j)))) return "joint " + std::to_string(j) + " position not finite";
    if (!std::isfinite(r.jointVelocity(static_cast<int>(j)))) return "joint " + std::to_string(j) + " velocity not finite";
  }
  return "";
}

/// A fan of `rays` rays through the scene: "" when every distance is a number.
inline std::string brokenCastPromise(tianracer_sim::RayCaster* caster, const tianracer_sim::Scene& scene,
                                     int rays) {
  caster->update(scene);
  std::vector<Eigen::Vector3f> dirs;
  for (int i = 0; i < rays; ++i) {
    const float a = static_cast<float>(2.0 * M_PI * i / rays);
    dirs.emplace_back(std::cos(a), std::sin(a), -0.05f);
  }
  std::vector<float> d(dirs.size());
  caster->castRays(Eigen::Vector3d(-1.0, 0.0, 0.3), dirs, 0.0f, 30.0f, d.data());
  for (float x : d) {
    if (std::isnan(x)) return "a ray distance is NaN";
  }
  return "";
}

/// `robot` (its model loaded, its spawn pose set) on `world`: the first broken promise, as
/// "step <k>: <what>", or "".
inline std::string replayRobot(tianracer_sim::RobotConfig robot, const tianracer_sim::WorldDescription& world,
                               const tianracer_sim::WarningSink& warn, const SimReplay& how = {}) {
  using namespace tianracer_sim;
  Simulation sim(physicsOptionsFor(world), warn);
  addWorldToPhysics(world, &sim.physics(), warn);
  Scene scene;
  addToScene(world, scene);
  SimRobot& added = sim.addRobot(robot);
  const RobotSceneBodies bodies = addRobotToScene(added.model, added.name, &scene);
  const PhysicsRobot& r = sim.physics().robot(added.id);
  RayCaster caster;
  for (int k = 1; k <= how.steps; ++k) {
    sim.step();
    std::string broken = brokenBodyPromise(r);
    if (broken.empty() && k % how.cast_every == 0) {
      updateRobotScene(r, bodies, &scene);
      broken = brokenCastPromise(&caster, scene, how.rays);
    }
    if (!broken.empty()) return "step " + std::to_string(k) + ": " + broken;
  }
  return "";
}

/// `world`'s models simulated together: the first broken promise, as "step <k>: <what>", or "".
inline std::string replayWorld(const tianracer_sim::WorldDescription& world,
                               const tianracer_sim::WarningSink& warn, const SimReplay& how = {}) {
  using namespace tianracer_sim;
  Simulation sim(physicsOptionsFor(world), warn);
  addWorldToPhysics(world, &sim.physics(), warn);
  Scene scene;
  addToScene(world, scene);
  RayCaster caster;
  for (int k = 1; k <= how.steps; ++k) {
    sim.step();
    std::string broken;
    for (int b = 0; broken.empty() && b < sim.physics().freeBodyCount(); ++b) {
      if (sim.physics().hasFreeBody(b)) broken = brokenBodyPromise(sim.physics().freeBody(b));
    }
    if (broken.empty() && k % how.cast_every == 0) {
      updateFreeBodyScene(sim.physics(), &scene);
      broken = brokenCastPromise(&caster, scene, how.rays);
    }
    if (!broken.empty()) return "step " + std::to_string(k) + ": " + broken;
  }
  return "";
}

}  // namespace tianracer_sim_fuzz

#endif  // TIANRACER_SIM_FUZZ_SIM_REPLAY_H
