// The judgement the corpus tools share (model_corpus: one model on the ground plane;
// world_corpus: every model of a world; docs/gazebo_models.md, docs/gazebo_worlds.md): a model's
// collision bounds and base, its motion over the sim, and the verdict. Header-only, for the tools
// and their unit test (test_tools_corpus_judge).
#pragma once

#include <algorithm>
#include <chrono>
#include <stdexcept>
#include <cmath>
#include <cstdlib>
#include <functional>
#include <iostream>
#include <limits>
#include <sstream>
#include <string>
#include <vector>

#include <Eigen/Geometry>

#include "tianracer_sim/mesh/mesh_loader.h"
#include "tianracer_sim/sim/simulation.h"
#include "tianracer_sim/sim/world_physics.h"
#include "tianracer_sim/world/world.h"

namespace tianracer_sim {
namespace corpus {

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
inline std::vector<Eigen::Vector3d> shapePoints(const Shape& s, const Eigen::Isometry3d& X_WS) {
  std::vector<Eigen::Vector3d> out;
  switch (s.type) {
    case ShapeType::kBox:
      for (int i = 0; i < 8; ++i) {
        const Eigen::Vector3d c((i & 1 ? 0.5 : -0.5) * s.size.x(), (i & 2 ? 0.5 : -0.5) * s.size.y(),
                                (i & 4 ? 0.5 : -0.5) * s.size.z());
        out.push_back(X_WS * c);
      }
      break;
    case ShapeType::kCylinder:
      for (int k = 0; k < 64; ++k) {
        const double a = 2.0 * M_PI * k / 64;
        for (double z : {-0.5 * s.length, 0.5 * s.length})
          out.push_back(X_WS * Eigen::Vector3d(s.radius * std::cos(a), s.radius * std::sin(a), z));
      }
      break;
    case ShapeType::kSphere:  // its poles and equator: exact bounds, one lowest point
      for (int i = 0; i < 3; ++i) {
        for (double sign : {-1.0, 1.0}) out.push_back(X_WS.translation() + sign * s.radius * Eigen::Vector3d::Unit(i));
      }
      break;
    case ShapeType::kMesh:
      for (const Eigen::Vector3f& v : meshOf(s)->vertices) out.push_back(X_WS * v.cast<double>());
      break;
    case ShapeType::kPlane:
      break;
  }
  return out;
}

inline double cross(const Eigen::Vector2d& o, const Eigen::Vector2d& a, const Eigen::Vector2d& b) {
  return (a - o).x() * (b - o).y() - (a - o).y() * (b - o).x();
}

// Convex hull (Andrew's monotone chain), counter-clockwise.
inline std::vector<Eigen::Vector2d> hull2d(std::vector<Eigen::Vector2d> p) {
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

inline double area(const std::vector<Eigen::Vector2d>& h) {
  double a = 0.0;
  for (std::size_t i = 0; i < h.size(); ++i) {
    const Eigen::Vector2d& p = h[i];
    const Eigen::Vector2d& q = h[(i + 1) % h.size()];
    a += p.x() * q.y() - q.x() * p.y();
  }
  return 0.5 * std::abs(a);
}

inline bool inside(const std::vector<Eigen::Vector2d>& h, const Eigen::Vector2d& p) {
  if (h.size() < 3) return false;
  for (std::size_t i = 0; i < h.size(); ++i) {
    if (cross(h[i], h[(i + 1) % h.size()], p) < 0) return false;
  }
  return true;
}

inline double angleBetween(const Eigen::Isometry3d& a, const Eigen::Isometry3d& b) {
  return Eigen::AngleAxisd(a.linear().transpose() * b.linear()).angle();
}

inline std::string fmt(double v, int precision = 3) {
  std::ostringstream os;
  os.setf(std::ios::fixed);
  os.precision(precision);
  os << (std::abs(v) < 0.5 * std::pow(10.0, -precision) ? 0.0 : v);
  return os.str();
}

inline std::string vec(const Eigen::Vector3d& v, int precision = 3) {
  return fmt(v.x(), precision) + " " + fmt(v.y(), precision) + " " + fmt(v.z(), precision);
}

// '|' would end a Markdown table cell; the corpus folder is written <models>.
inline std::string cell(std::string s, const std::string& models_dir) {
  for (std::size_t at; (at = s.find(models_dir)) != std::string::npos;) s.replace(at, models_dir.size(), "<models>");
  std::replace(s.begin(), s.end(), '|', '/');
  std::replace(s.begin(), s.end(), '\n', ' ');
  return s;
}

// One model: what it is (describe), how it moved (track), what that means (judge*).
struct Judged {
  std::string name;
  bool is_static = true;
  bool free_body = false;     // simulated as moving bodies (with or without a world joint)
  bool world_joint = false;   // a joint with the world as its parent holds it in place
  std::string held_static;    // why the physics holds a dynamic model static, if it does
  int collisions = 0;
  int plugins = 0;            // its own <plugin>s (they may move it: no verdict then)
  Bounds bounds;
  bool flat = false, on_ground = false;
  double base_z = 0.0;  // lowest collision point at the default pose
  std::string base;     // what the flat-base test saw
  Eigen::Isometry3d X_start = Eigen::Isometry3d::Identity();
  Eigen::Isometry3d X_settled = Eigen::Isometry3d::Identity();  // after --settle
  Eigen::Isometry3d X_end = Eigen::Isometry3d::Identity();      // after --hold
  double max_distance = 0.0, max_angle = 0.0;  // from the start, over the whole run
  // From the pose at the start of the last window (world_corpus: the last 10 s) to every later one.
  Eigen::Isometry3d X_window = Eigen::Isometry3d::Identity();
  double window_distance = 0.0, window_angle = 0.0;
  std::string verdict, why;
};

inline void judgeBase(const ModelDescription& m, Judged* r) {
  std::vector<Eigen::Vector3d> points;
  double mass = 0.0;
  Eigen::Vector3d com = Eigen::Vector3d::Zero();
  for (const LinkDescription& l : m.links) {
    const Eigen::Isometry3d X_WL = m.X_WM * l.X_ML;
    for (const CollisionDescription& c : l.collisions) {
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

// The static facts of a model at its default pose: static, world joints, collisions, bounds, base.
inline void describe(const ModelDescription& m, Judged* r) {
  r->name = m.name;
  r->is_static = m.is_static;
  r->plugins = static_cast<int>(m.plugins.size());
  for (const JointDescription& j : m.joints) r->world_joint |= j.parent == "world";
  for (const LinkDescription& l : m.links) {
    const Eigen::Isometry3d X_WL = m.X_WM * l.X_ML;
    for (const CollisionDescription& c : l.collisions) {
      ++r->collisions;
      for (const Eigen::Vector3d& p : shapePoints(c.shape, X_WL * c.X_LS)) r->bounds.add(p);
    }
  }
  judgeBase(m, r);
}

// One sampled pose of its base; `in_window`: the sample lies in the last window.
inline void track(const Eigen::Isometry3d& X, bool in_window, Judged* r) {
  if (!X.matrix().allFinite()) {
    r->max_distance = r->window_distance = std::numeric_limits<double>::infinity();
    return;
  }
  r->max_distance = std::max(r->max_distance, (X.translation() - r->X_start.translation()).norm());
  r->max_angle = std::max(r->max_angle, angleBetween(r->X_start, X));
  if (!in_window) {
    r->X_window = X;
    return;
  }
  r->window_distance = std::max(r->window_distance, (X.translation() - r->X_window.translation()).norm());
  r->window_angle = std::max(r->window_angle, angleBetween(r->X_window, X));
}

// The verdicts every corpus gives first: no collision, static, welded or held static. true: given.
inline bool judgeFixed(Judged* r) {
  if (r->collisions == 0) {
    r->verdict = "loads";
    r->why = "no collision";
  } else if (r->is_static) {
    r->verdict = "static";
  } else if (!r->free_body) {
    r->verdict = "static";
    r->why = r->held_static.empty() ? "welded to the world by fixed joints" : "held static: " + r->held_static;
  } else {
    return false;
  }
  return true;
}

// model_corpus: a model alone on the ground plane, after settle + hold seconds (judgeFixed first).
inline void judgeOnGround(Judged* r, double settle, double hold) {
  const bool rests = r->max_distance <= kRestDistance && r->max_angle <= kRestAngle;
  // Where a flat base ends: the start pose moved up or down until the base meets the ground.
  Eigen::Isometry3d X_rest = r->X_start;
  X_rest.translation().z() -= r->base_z;
  const double end_distance = (r->X_end.translation() - X_rest.translation()).norm();
  const double end_angle = angleBetween(X_rest, r->X_end);
  const std::string hold_s = fmt(std::max(settle, hold), 0) + " s";
  if (judgeFixed(r)) return;
  if (r->world_joint) {
    // Its other joints are simulated: it must stay where its world joint holds it, unless
    // something in it swings (then it moves, as a pendulum does in Gazebo).
    r->verdict = rests ? "rests" : "moves";
    r->why = "joined to the world by a joint";
    if (!rests) {
      r->why += "; its base moved up to " + fmt(r->max_distance * 100.0, 1) + " cm and " +
               fmt(r->max_angle, 3) + " rad within " + hold_s;
    }
  } else if (r->flat && r->on_ground) {
    r->verdict = rests ? "rests" : "differs";
    if (!rests) {
      r->why = "moved up to " + fmt(r->max_distance * 100.0, 1) + " cm and " + fmt(r->max_angle, 3) +
              " rad from its start within " + hold_s;
    }
  } else if (r->flat) {
    // Starts above the ground (falls) or in it (is pushed out), then must rest on its base.
    const bool settles = end_distance <= kRestDistance && end_angle <= kRestAngle;
    r->verdict = settles ? "settles" : "differs";
    r->why = std::string(r->base_z > 0 ? "starts " + fmt(r->base_z * 100.0, 1) + " cm above"
                                     : "starts " + fmt(-r->base_z * 100.0, 1) + " cm in") +
            " the ground";
    if (!settles) {
      r->why += "; after " + hold_s + " " + fmt(end_distance * 100.0, 1) + " cm and " +
               fmt(end_angle, 3) + " rad from resting on its base there";
    }
  } else {
    r->verdict = "moves";
    r->why = "no flat base";
  }
}

// world_corpus: a model among others, where its world puts it (the ground may be another model).
//   rests: within 1 cm and 0.05 rad of its start over the whole run;
//   settles: moved more, then within 1 cm and 0.05 rad of one pose over the last window;
//   moves: neither, with no flat base or on a joint to the world (balls, robots on wheels,
//     pendulums), or with <plugin>s of its own (they may drive it): no verdict;
//   differs: neither, with a flat base: it should have come to rest.
inline void judgeInWorld(Judged* r, double seconds, double window) {
  if (judgeFixed(r)) return;
  const auto moved = [](double d, double a) {
    return fmt(d * 100.0, 1) + " cm and " + fmt(a, 3) + " rad";
  };
  if (r->max_distance <= kRestDistance && r->max_angle <= kRestAngle) {
    r->verdict = "rests";
  } else if (r->window_distance <= kRestDistance && r->window_angle <= kRestAngle) {
    r->verdict = "settles";
    r->why = "moved up to " + moved(r->max_distance, r->max_angle) + ", still over the last " + fmt(window, 0) + " s";
  } else {
    const std::string how = "still moving: " + moved(r->window_distance, r->window_angle) + " in the last " +
                            fmt(window, 0) + " s of " + fmt(seconds, 0);
    if (r->plugins > 0) {
      r->verdict = "moves";
      r->why = "has " + std::to_string(r->plugins) + " plugin(s) of its own; " + how;
    } else if (r->world_joint) {
      r->verdict = "moves";
      r->why = "joined to the world by a joint; " + how;
    } else if (!r->flat) {
      r->verdict = "moves";
      r->why = "no flat base; " + how;
    } else {
      r->verdict = "differs";
      r->why = how;
    }
  }
}

// Thrown by runWorld when its wall-clock budget is spent (a tool's guard, not a verdict on motion).
struct OutOfTime : std::runtime_error {
  using std::runtime_error::runtime_error;
};

// Every model of `world` simulated together for `seconds` of sim (poses sampled every 10 ms),
// judged by judgeInWorld. Throws what Simulation or addWorldToPhysics throw, and OutOfTime
// after `wall_limit` seconds of wall clock (0: none).
inline std::vector<Judged> runWorld(const WorldDescription& world, double seconds, double window,
                                    const std::function<void(const std::string&)>& warn_out = {},
                                    double wall_limit = 0.0) {
  const auto t0 = std::chrono::steady_clock::now();
  std::vector<Judged> out(world.models.size());
  for (std::size_t i = 0; i < world.models.size(); ++i) describe(world.models[i], &out[i]);
  const auto warn = [&](const std::string& w) {
    if (warn_out) warn_out(w);
    if (w.find("held static") == std::string::npos) return;
    for (Judged& r : out)
      if (r.held_static.empty() && w.find("'" + r.name + "'") != std::string::npos) r.held_static = w;
  };
  Simulation sim(physicsOptionsFor(world), warn);
  addWorldToPhysics(world, &sim.physics(), warn);
  std::vector<const PhysicsRobot*> bodies(out.size(), nullptr);
  for (std::size_t i = 0; i < out.size(); ++i) {
    bodies[i] = sim.findModel(out[i].name);
    out[i].free_body = bodies[i] != nullptr;
    out[i].X_start = out[i].X_window = out[i].X_end = bodies[i] ? bodies[i]->basePose() : world.models[i].X_WM;
  }
  const int steps = static_cast<int>(std::lround(seconds / sim.dt()));
  const int window_start = static_cast<int>(std::lround((seconds - window) / sim.dt()));
  const int every = std::max(1, static_cast<int>(std::lround(0.01 / sim.dt())));
  for (int k = 1; k <= steps; ++k) {
    sim.step();
    if (k % every != 0 && k != window_start && k != steps) continue;
    if (wall_limit > 0.0 &&
        std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count() > wall_limit) {
      throw OutOfTime("stopped after " + fmt(k * sim.dt(), 1) + " s of sim: " + fmt(wall_limit, 0) +
                      " s of wall clock spent");
    }
    for (std::size_t i = 0; i < out.size(); ++i)
      if (bodies[i]) track(bodies[i]->basePose(), k > window_start, &out[i]);
  }
  for (std::size_t i = 0; i < out.size(); ++i) {
    if (bodies[i]) out[i].X_end = out[i].X_settled = bodies[i]->basePose();
    judgeInWorld(&out[i], seconds, window);
  }
  return out;
}

/// The command line: the value of option argv[*i], the next word (*i is moved onto it); with
/// none, "<option> needs a value" on stderr and exit status 2.
inline std::string optionValue(int argc, char** argv, int* i) {
  if (*i + 1 >= argc) {
    std::cerr << argv[*i] << " needs a value\n";
    std::exit(2);
  }
  return argv[++*i];
}

}  // namespace corpus
}  // namespace tianracer_sim
