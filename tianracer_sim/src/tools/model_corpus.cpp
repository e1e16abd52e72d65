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

#include "tianracer_sim/mesh/mesh_loader.h"
#include "tianracer_sim/sim/simulation.h"
#include "tianracer_sim/sim/world_physics.h"
#include "tianracer_sim/world/world.h"

namespace ts = tianracer_sim;
namespace fs = std::filesystem;

namespace {

constexpr double kRestDistance = 0.01;  // m
constexpr double kRestAngle = 0.05;     // rad
constexpr double kBaseBand = 0.001;     // m: collision points this close to the lowest one
constexpr double kOnGround = 0.01;      // m: a base this close to z = 0 starts on the ground
constexpr double kMinBaseArea = 1e-4;   // m^2: below this a base is a point or an edge

struct Bounds {
  Eigen::Vector3d lo = Eigen::Vector3d::Constant(std::numeric_limits<double>::infinity());
  Eigen::Vector3d hi = -lo;
  bool empty() const { return !(lo.x() <= hi.x()); }
  void add(const Eigen::Vector3d& p) {
    lo = lo.cwiseMin(p);
    hi = hi.cwiseMax(p);
  }
};

// Points of a collision shape in the world: a box's corners, a cylinder's rims (64 points each),
// a sphere's poles and equator points, a mesh's vertices (planes: none).
std::vector<Eigen::Vector3d> shapePoints(const ts::Shape& s, const Eigen::Isometry3d& X_WS) {
  std::vector<Eigen::Vector3d> out;
  switch (s.type) {
    case ts::ShapeType::kBox:
      for (int i = 0; i < 8; ++i) {
        const Eigen::Vector3d c((i & 1 ? 0.5 : -0.5) * s.size.x(), (i & 2 ? 0.5 : -0.5) * s.size.y(),
                                (i & 4 ? 0.5 : -0.5) * s.size.z());
        out.push_back(X_WS * c);
      }
      break;
    case ts::ShapeType::kCylinder:
      for (int k = 0; k < 64; ++k) {
        const double a = 2.0 * M_PI * k / 64;
        for (double z : {-0.5 * s.length, 0.5 * s.length})
          out.push_back(X_WS * Eigen::Vector3d(s.radius * std::cos(a), s.radius * std::sin(a), z));
      }
      break;
    case ts::ShapeType::kSphere:  // its poles and equator: exact bounds, one lowest point
      for (int i = 0; i < 3; ++i) {
        for (double sign : {-1.0, 1.0}) out.push_back(X_WS.translation() + sign * s.radius * Eigen::Vector3d::Unit(i));
      }
      break;
    case ts::ShapeType::kMesh:
      for (const Eigen::Vector3f& v : ts::meshOf(s)->vertices) out.push_back(X_WS * v.cast<double>());
      break;
    case ts::ShapeType::kPlane:
      break;
  }
  return out;
}

double cross(const Eigen::Vector2d& o, const Eigen::Vector2d& a, const Eigen::Vector2d& b) {
  return (a - o).x() * (b - o).y() - (a - o).y() * (b - o).x();
}

// Convex hull (Andrew's monotone chain), counter-clockwise.
std::vector<Eigen::Vector2d> hull2d(std::vector<Eigen::Vector2d> p) {
  std::sort(p.begin(), p.end(), [](const Eigen::Vector2d& a, const Eigen::Vector2d& b) {
    return a.x() < b.x() || (a.x() == b.x() && a.y() < b.y());
  });
  if (p.size() < 3) return p;
  std::vector<Eigen::Vector2d> h(2 * p.size());
  std::size_t k = 0;
  for (std::size_t i = 0; i < p.size(); ++i) {
    while (k >= 2 && cross(h[k - 2], h[k - 1], p[i]) <= 0) --k;
    h[k++] = p[i];
  }
  for (std::size_t i = p.size() - 1, t = k + 1; i > 0; --i) {
    while (k >= t && cross(h[k - 2], h[k - 1], p[i - 1]) <= 0) --k;
    h[k++] = p[i - 1];
  }
  h.resize(k - 1);
  return h;
}

double area(const std::vector<Eigen::Vector2d>& h) {
  double a = 0.0;
  for (std::size_t i = 0; i < h.size(); ++i) {
    const Eigen::Vector2d& p = h[i];
    const Eigen::Vector2d& q = h[(i + 1) % h.size()];
    a += p.x() * q.y() - q.x() * p.y();
  }
  return 0.5 * std::abs(a);
}

bool inside(const std::vector<Eigen::Vector2d>& h, const Eigen::Vector2d& p) {
  if (h.size() < 3) return false;
  for (std::size_t i = 0; i < h.size(); ++i) {
    if (cross(h[i], h[(i + 1) % h.size()], p) < 0) return false;
  }
  return true;
}

double angleBetween(const Eigen::Isometry3d& a, const Eigen::Isometry3d& b) {
  return Eigen::AngleAxisd(a.linear().transpose() * b.linear()).angle();
}

std::string fmt(double v, int precision = 3) {
  std::ostringstream os;
  os.setf(std::ios::fixed);
  os.precision(precision);
  os << (std::abs(v) < 0.5 * std::pow(10.0, -precision) ? 0.0 : v);
  return os.str();
}

std::string vec(const Eigen::Vector3d& v, int precision = 3) {
  return fmt(v.x(), precision) + " " + fmt(v.y(), precision) + " " + fmt(v.z(), precision);
}

// '|' would end a Markdown table cell; the corpus folder is written <models>.
std::string cell(std::string s, const std::string& models_dir) {
  for (std::size_t at; (at = s.find(models_dir)) != std::string::npos;) s.replace(at, models_dir.size(), "<models>");
  std::replace(s.begin(), s.end(), '|', '/');
  std::replace(s.begin(), s.end(), '\n', ' ');
  return s;
}

struct Result {
  std::string name;
  bool loads = false;
  std::string error;                // why it does not load
  std::vector<std::string> left_out;  // errors that left part of it out
  int warnings = 0;
  bool is_static = true;
  bool free_body = false;     // simulated as moving bodies (with or without a world joint)
  bool world_joint = false;   // a joint with the world as its parent holds it in place
  std::string held_static;    // why the physics holds a dynamic model static, if it does
  int collisions = 0;
  Bounds bounds;
  bool flat = false, on_ground = false;
  double base_z = 0.0;  // lowest collision point at the default pose
  std::string base;     // what the flat-base test saw
  Eigen::Isometry3d X_start = Eigen::Isometry3d::Identity();
  Eigen::Isometry3d X_settled = Eigen::Isometry3d::Identity();  // after --settle
  Eigen::Isometry3d X_end = Eigen::Isometry3d::Identity();      // after --hold
  double max_distance = 0.0, max_angle = 0.0;  // from the start, over settle + hold
  std::string verdict, why;
  double load_ms = 0.0, sim_ms = 0.0;
};

void judgeBase(const ts::ModelDescription& m, Result* r) {
  std::vector<Eigen::Vector3d> points;
  double mass = 0.0;
  Eigen::Vector3d com = Eigen::Vector3d::Zero();
  for (const ts::LinkDescription& l : m.links) {
    const Eigen::Isometry3d X_WL = m.X_WM * l.X_ML;
    for (const ts::CollisionDescription& c : l.collisions) {
      for (const Eigen::Vector3d& p : shapePoints(c.shape, X_WL * c.X_LS)) points.push_back(p);
    }
    mass += l.inertial.mass;
    com += l.inertial.mass * (X_WL * l.inertial.X_LI).translation();
  }
  if (points.empty()) {
    r->base = "no collision";
    return;
  }
  com /= mass;
  double zmin = std::numeric_limits<double>::infinity();
  for (const Eigen::Vector3d& p : points) zmin = std::min(zmin, p.z());
  std::vector<Eigen::Vector2d> base;
  for (const Eigen::Vector3d& p : points) {
    if (p.z() <= zmin + kBaseBand) base.push_back(p.head<2>());
  }
  const std::vector<Eigen::Vector2d> h = hull2d(base);
  const double a = h.size() >= 3 ? area(h) : 0.0;
  r->base_z = zmin;
  r->on_ground = std::abs(zmin) <= kOnGround;
  const bool com_inside = inside(h, com.head<2>());
  r->flat = a >= kMinBaseArea && com_inside;
  std::ostringstream os;
  os << "base area " << fmt(a * 1e4, 1) << " cm2 at z " << fmt(zmin);
  if (a >= kMinBaseArea && !com_inside) os << ", centre of mass outside it";
  r->base = os.str();
}

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
  r.is_static = m.is_static;
  for (const ts::JointDescription& j : m.joints) r.world_joint |= j.parent == "world";
  for (const ts::LinkDescription& l : m.links) {
    const Eigen::Isometry3d X_WL = m.X_WM * l.X_ML;
    for (const ts::CollisionDescription& c : l.collisions) {
      ++r.collisions;
      for (const Eigen::Vector3d& p : shapePoints(c.shape, X_WL * c.X_LS)) r.bounds.add(p);
    }
  }
  judgeBase(m, &r);
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

  const bool rests = r.max_distance <= kRestDistance && r.max_angle <= kRestAngle;
  // Where a flat base ends: the start pose moved up or down until the base meets the ground.
  Eigen::Isometry3d X_rest = r.X_start;
  X_rest.translation().z() -= r.base_z;
  const double end_distance = (r.X_end.translation() - X_rest.translation()).norm();
  const double end_angle = angleBetween(X_rest, r.X_end);
  const std::string hold_s = fmt(std::max(settle, hold), 0) + " s";
  if (r.collisions == 0) {
    r.verdict = "loads";
    r.why = "no collision";
  } else if (r.is_static) {
    r.verdict = "static";
  } else if (!r.free_body) {
    r.verdict = "static";
    r.why = r.held_static.empty() ? "welded to the world by fixed joints" : "held static: " + r.held_static;
  } else if (r.world_joint) {
    // Its other joints are simulated: it must stay where its world joint holds it, unless
    // something in it swings (then it moves, as a pendulum does in Gazebo).
    r.verdict = rests ? "rests" : "moves";
    r.why = "joined to the world by a joint";
    if (!rests) {
      r.why += "; its base moved up to " + fmt(r.max_distance * 100.0, 1) + " cm and " +
               fmt(r.max_angle, 3) + " rad within " + hold_s;
    }
  } else if (r.flat && r.on_ground) {
    r.verdict = rests ? "rests" : "differs";
    if (!rests) {
      r.why = "moved up to " + fmt(r.max_distance * 100.0, 1) + " cm and " + fmt(r.max_angle, 3) +
              " rad from its start within " + hold_s;
    }
  } else if (r.flat) {
    // Starts above the ground (falls) or in it (is pushed out), then must rest on its base.
    const bool settles = end_distance <= kRestDistance && end_angle <= kRestAngle;
    r.verdict = settles ? "settles" : "differs";
    r.why = std::string(r.base_z > 0 ? "starts " + fmt(r.base_z * 100.0, 1) + " cm above"
                                     : "starts " + fmt(-r.base_z * 100.0, 1) + " cm in") +
            " the ground";
    if (!settles) {
      r.why += "; after " + hold_s + " " + fmt(end_distance * 100.0, 1) + " cm and " +
               fmt(end_angle, 3) + " rad from resting on its base there";
    }
  } else {
    r.verdict = "moves";
    r.why = "no flat base";
  }
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
    auto next = [&]() -> std::string {
      if (i + 1 >= argc) {
        std::cerr << a << " needs a value\n";
        std::exit(2);
      }
      return argv[++i];
    };
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
