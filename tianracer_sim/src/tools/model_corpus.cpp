// model_corpus: Gazebo's model library (github:osrf/gazebo_models, or any folder of model
// folders) through the ROS-free core, one model at a time, the way a user's world would hold it
// (docs/gazebo_models.md). Run by hand, not in CI:
//   model_corpus <models_dir> [--only NAME]... [--settle S] [--hold S] [--trace S] [--markdown FILE]
//                [--load-only]
// For every folder with a model.sdf: a world with model://ground_plane and an <include> of the
// model at its default pose is loaded (world loader), added to a Simulation (sim/world_physics)
// and stepped. Reported: whether it loads (and what was left out), its collision bounds, its
// pose after --settle seconds (3) and, for a dynamic model whose collision base is flat (the
// lowest collision points span a polygon of at least 1 cm2 around the centre of mass):
//   on the ground at its default pose: whether it rests (within 1 cm and 0.05 rad of its start
//   for --hold seconds (30));
//   above or in the ground: whether it ends resting on its base (within 1 cm and 0.05 rad of
//   its start pose moved until the base meets the ground, after --hold seconds).
// The last lines time the loading of the whole corpus (a benchmark, not a test; --load-only
// skips the physics for it) and name the slowest models to load.
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <limits>
#include <map>
#include <sstream>
#include <string>
#include <vector>

#include <Eigen/Geometry>

#include "corpus_judge.h"

namespace ts = tianracer_sim;
namespace fs = std::filesystem;

namespace {

using namespace ts::corpus;  // corpus_judge.h: shared with world_corpus

struct Result : Judged {
  bool loads = false;
  std::string error;                // why it does not load
  std::vector<std::string> left_out;  // errors that left part of it out
  int warnings = 0;
  double load_ms = 0.0, sim_ms = 0.0;
};

double g_trace = 0.0;  // --trace S: print the base and joints every S seconds (0: not)

Result run(const std::string& models_dir, const std::string& name, double settle, double hold,
           bool load_only) {
  Result r;
  r.name = name;
  const std::string xml = "<sdf version='1.6'><world name='corpus'>"
                          "<include><uri>model://ground_plane</uri></include>"
                          "<include><uri>model://" + name + "</uri></include></world></sdf>";
  ts::WorldLoadOptions options;
  options.model_paths = {models_dir};
  options.warn = [&](const std::string&) { ++r.warnings; };
  options.error = [&](const std::string& e) { r.left_out.push_back(e); };
  const auto t0 = std::chrono::steady_clock::now();
  ts::WorldDescription world;
  try {
    world = ts::loadWorldString(xml, "corpus:" + name, models_dir, options);
    // Every mesh a sensor or the physics would use, loaded now (cached): part of loading.
    for (const ts::ModelDescription& m : world.models)
      for (const ts::LinkDescription& l : m.links) {
        for (const auto& c : l.collisions)
          if (c.shape.type == ts::ShapeType::kMesh) ts::meshOf(c.shape);
        for (const auto& v : l.visuals)
          if (v.shape.type == ts::ShapeType::kMesh) ts::meshWithMaterialsOf(v.shape);
      }
  } catch (const std::exception& e) {
    r.error = e.what();
    r.load_ms = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
    r.verdict = "fails";
    r.why = r.error;
    return r;
  }
  r.load_ms = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
  r.loads = true;
  if (world.models.empty()) {
    r.verdict = "left out";
    r.why = r.left_out.empty() ? "nothing to load" : r.left_out.front();
    return r;
  }
  const ts::ModelDescription& m = world.models.front();
  describe(m, &r);
  r.name = name;  // the folder, as before (describe takes the model's own name)
  if (load_only) {
    r.verdict = "loads";
    return r;
  }

  const auto t1 = std::chrono::steady_clock::now();
  try {
    const auto warn = [&](const std::string& w) {
      ++r.warnings;
      if (r.held_static.empty() && w.find("held static") != std::string::npos) r.held_static = w;
    };
    ts::Simulation sim(ts::physicsOptionsFor(world), warn);
    ts::addWorldToPhysics(world, &sim.physics(), warn);
    const ts::PhysicsRobot* body = sim.findModel(m.name);
    if (body) r.X_start = body->basePose();
    r.free_body = body != nullptr;
    const int settle_steps = static_cast<int>(std::lround(settle / sim.dt()));
    const int hold_steps = static_cast<int>(std::lround(hold / sim.dt()));
    const int every = std::max(1, static_cast<int>(std::lround(0.01 / sim.dt())));
    for (int k = 1; body && k <= std::max(settle_steps, hold_steps); ++k) {
      sim.step();
      if (k % every == 0 || k == settle_steps) {
        const Eigen::Isometry3d X = body->basePose();
        if (!X.matrix().allFinite()) {
          r.max_distance = std::numeric_limits<double>::infinity();
          break;
        }
        r.max_distance = std::max(r.max_distance, (X.translation() - r.X_start.translation()).norm());
        r.max_angle = std::max(r.max_angle, angleBetween(r.X_start, X));
      }
      if (k == settle_steps) r.X_settled = body->basePose();
      if (g_trace > 0.0 && k % std::max(1, static_cast<int>(std::lround(g_trace / sim.dt()))) == 0) {
        // --trace: the base's position and every joint's position and rate, for a "why".
        const Eigen::Vector3d p = body->basePose().translation();
        std::cerr << "t " << fmt(k * sim.dt(), 2) << " base " << fmt(p.x(), 5) << " " << fmt(p.y(), 5)
                  << " " << fmt(p.z(), 5);
        for (int j = 0; j < static_cast<int>(body->joints().size()); ++j)
          std::cerr << " | " << body->joints()[j].name << " " << fmt(body->jointPosition(j), 5)
                    << " " << fmt(body->jointVelocity(j), 5);
        std::cerr << "\n";
      }
    }
    if (body) r.X_end = body->basePose();
    if (!body) r.X_end = r.X_settled = r.X_start = m.X_WM;
  } catch (const std::exception& e) {
    r.verdict = "fails";
    r.why = std::string("physics: ") + e.what();
    return r;
  }
  r.sim_ms = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t1).count();

  if (!judgeFixed(&r)) judgeOnGround(&r, settle, hold);
  if (!r.left_out.empty()) r.why += (r.why.empty() ? "" : "; ") + std::to_string(r.left_out.size()) +
                                    " left out: " + r.left_out.front();
  return r;
}

}  // namespace

int main(int argc, char** argv) {
  std::string dir, markdown;
  std::vector<std::string> only;
  double settle = 3.0, hold = 30.0;
  bool load_only = false;
  for (int i = 1; i < argc; ++i) {
    const std::string a = argv[i];
    auto next = [&]() { return optionValue(argc, argv, &i); };
    if (a == "--only") only.push_back(next());
    else if (a == "--settle") settle = std::stod(next());
    else if (a == "--hold") hold = std::stod(next());
    else if (a == "--trace") g_trace = std::stod(next());
    else if (a == "--markdown") markdown = next();
    else if (a == "--load-only") load_only = true;
    else if (!a.empty() && a[0] == '-') {
      std::cerr << "usage: model_corpus <models_dir> [--only NAME]... [--settle S] [--hold S] "
                   "[--markdown FILE] [--load-only]\n";
      return 2;
    } else dir = a;
  }
  if (dir.empty() || !fs::is_directory(dir)) {
    std::cerr << "model_corpus: give the folder of model folders (e.g. an export of "
                 "github:osrf/gazebo_models)\n";
    return 2;
  }
  dir = fs::absolute(dir).lexically_normal().string();
  std::vector<std::string> names;
  for (const auto& e : fs::directory_iterator(dir)) {
    if (!e.is_directory() || !fs::exists(e.path() / "model.sdf")) continue;
    const std::string n = e.path().filename().string();
    if (n == "ground_plane" || n == "sun") continue;  // the world's built-ins
    if (only.empty() || std::find(only.begin(), only.end(), n) != only.end()) names.push_back(n);
  }
  std::sort(names.begin(), names.end());

  std::vector<Result> results;
  std::map<std::string, int> counts;
  double load_ms = 0.0, sim_ms = 0.0;
  for (const std::string& n : names) {
    std::cerr << n << "... " << std::flush;
    results.push_back(run(dir, n, settle, hold, load_only));
    const Result& r = results.back();
    std::cerr << r.verdict << (r.why.empty() ? "" : " (" + r.why.substr(0, 160) + ")") << "\n";
    ++counts[r.verdict];
    load_ms += r.load_ms;
    sim_ms += r.sim_ms;
  }

  std::ostringstream md;
  md << "| model | loads | static | collision bounds min .. max (m) | base | after " << fmt(settle, 0)
     << " s: xyz (m), tilt (rad), moved (cm) | verdict | why |\n|---|---|---|---|---|---|---|---|\n";
  for (const Result& r : results) {
    const double tilt = std::acos(std::clamp(
        (r.X_settled.linear() * Eigen::Vector3d::UnitZ()).dot(r.X_start.linear() * Eigen::Vector3d::UnitZ()),
        -1.0, 1.0));
    md << "| " << r.name << " | " << (r.loads ? (r.left_out.empty() ? "yes" : "partly") : "no") << " | "
       << (r.loads ? (r.is_static ? "yes" : "no") : "") << " | "
       << (r.bounds.empty() ? std::string() : vec(r.bounds.lo, 2) + " .. " + vec(r.bounds.hi, 2)) << " | "
       << cell(r.base, dir) << " | "
       << (r.loads && r.collisions
               ? vec(r.X_settled.translation()) + ", " + fmt(tilt) + ", " +
                     fmt((r.X_settled.translation() - r.X_start.translation()).norm() * 100.0, 1)
               : std::string())
       << " | " << r.verdict << " | " << cell(r.why, dir) << " |\n";
  }
  md << "\n" << results.size() << " models:";
  for (const auto& kv : counts) md << " " << kv.second << " " << kv.first << ",";
  md.seekp(-1, std::ios::cur);
  md << ".\n\nLoading the whole corpus (world loader and every mesh, first load): " << fmt(load_ms, 0)
     << " ms";
  if (!load_only) {
    md << "; physics set-up and " << fmt(std::max(settle, hold), 0) << " s of sim per model: "
       << fmt(sim_ms / 1000.0, 1) << " s";
  }
  std::vector<const Result*> slow;
  for (const Result& r : results) slow.push_back(&r);
  std::sort(slow.begin(), slow.end(), [](const Result* a, const Result* b) { return a->load_ms > b->load_ms; });
  md << ". Slowest to load:";
  for (std::size_t i = 0; i < std::min<std::size_t>(5, slow.size()); ++i)
    md << (i ? "," : "") << " " << slow[i]->name << " " << fmt(slow[i]->load_ms, 0) << " ms";
  md << ".\n";
  std::cout << md.str();
  if (!markdown.empty()) std::ofstream(markdown) << md.str();
  return 0;
}
