// Ray casting against analytic scenes: every beam within 1 mm of the exact distance (corners
// included), the range model of ray_sensor.h, noise statistics, determinism and moving bodies.
#include <sys/syscall.h>
#include <unistd.h>
#include <algorithm>
#include <cmath>
#include <cstring>
#include <ctime>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <sstream>
#include <limits>
#include <string>
#include <tuple>
#include <vector>

#include <gtest/gtest.h>

#include "tianracer_sim/lidar/ray_caster.h"
#include "tianracer_sim/plugins/ray/ray_sensor.h"

#include "lidar_test_support.h"

namespace tianracer_sim {
namespace {

constexpr double kInf = std::numeric_limits<double>::infinity();
const std::string kCube = std::string(TEST_DATA_DIR) + "/worlds/meshes/unit_cube.stl";

using test::seedHokuyo;

// The seed hokuyo with gaussian range noise N(mean, stddev).
RaySensorConfig noisyHokuyo(double mean, double stddev) {
  RaySensorConfig c = seedHokuyo();
  c.noise.type = "gaussian";
  c.noise.mean = mean;
  c.noise.stddev = stddev;
  return c;
}

Eigen::Isometry3d pose(double x, double y, double z, double yaw = 0.0, double pitch = 0.0) {
  Eigen::Isometry3d X = Eigen::Isometry3d::Identity();
  X.translation() = Eigen::Vector3d(x, y, z);
  X.linear() = (Eigen::AngleAxisd(yaw, Eigen::Vector3d::UnitZ()) *
                Eigen::AngleAxisd(pitch, Eigen::Vector3d::UnitY()))
                   .toRotationMatrix();
  return X;
}

SceneItem boxItem(int body, const Eigen::Isometry3d& X_BS, const Eigen::Vector3d& size) {
  SceneItem it;
  it.body = body;
  it.X_BS = X_BS;
  it.shape.type = ShapeType::kBox;
  it.shape.size = size;
  it.collision = true;
  it.visual = false;
  return it;
}

SceneItem cylinderItem(int body, const Eigen::Isometry3d& X_BS, double r, double length) {
  SceneItem it = boxItem(body, X_BS, Eigen::Vector3d::Zero());
  it.shape.type = ShapeType::kCylinder;
  it.shape.radius = r;
  it.shape.length = length;
  return it;
}

SceneItem sphereItem(int body, const Eigen::Isometry3d& X_BS, double r) {
  SceneItem it = boxItem(body, X_BS, Eigen::Vector3d::Zero());
  it.shape.type = ShapeType::kSphere;
  it.shape.radius = r;
  return it;
}

int addStatic(Scene& scene, const std::string& name) {
  SceneBody b;
  b.name = name + "::link";
  b.model = name;
  b.is_static = true;
  return scene.addBody(b);
}

/// A closed room, inner faces at x = x0, x1 and y = y0, y1; walls 0.1 thick, z 0 .. 1.
void addRoom(Scene& scene, double x0, double x1, double y0, double y1) {
  const int b = addStatic(scene, "room");
  const double cx = (x0 + x1) / 2, cy = (y0 + y1) / 2, w = x1 - x0 + 0.2, h = y1 - y0 + 0.2;
  scene.items.push_back(boxItem(b, pose(cx, y1 + 0.05, 0.5), {w, 0.1, 1.0}));
  scene.items.push_back(boxItem(b, pose(cx, y0 - 0.05, 0.5), {w, 0.1, 1.0}));
  scene.items.push_back(boxItem(b, pose(x1 + 0.05, cy, 0.5), {0.1, h, 1.0}));
  scene.items.push_back(boxItem(b, pose(x0 - 0.05, cy, 0.5), {0.1, h, 1.0}));
}

/// The seed hokuyo scanning with one default caster and one generator (seed 1) throughout, as
/// a sensor that keeps its caster between scans does.
struct SeedLidar {
  RayCaster caster;
  RaySensorConfig c = seedHokuyo();
  std::mt19937_64 rng{1};
  std::vector<float> scan(const Scene& scene, const Eigen::Isometry3d& X_WS) {
    return scanRays(caster, scene, X_WS, c, rng);
  }
};

// ---- Double-precision reference ---------------------------------------------------------------

// Each gives the first surface point at t >= t_min (the ray's start, range_min): from inside a
// solid that is its far side, as ODE's ray colliders report it.
double refBox(const Eigen::Isometry3d& X_WS, const Eigen::Vector3d& half, const Eigen::Vector3d& o,
              const Eigen::Vector3d& d, double t_min) {
  const Eigen::Isometry3d X_SW = X_WS.inverse();
  const Eigen::Vector3d os = X_SW * o, ds = X_SW.linear() * d;
  double t0 = -kInf, t1 = kInf;
  for (int k = 0; k < 3; ++k) {
    if (ds[k] == 0.0) {
      if (std::abs(os[k]) > half[k]) return kInf;
      continue;
    }
    double a = (-half[k] - os[k]) / ds[k], b = (half[k] - os[k]) / ds[k];
    if (a > b) std::swap(a, b);
    t0 = std::max(t0, a);
    t1 = std::min(t1, b);
  }
  if (t0 > t1 || t1 < t_min) return kInf;
  return t0 >= t_min ? t0 : t1;
}

double refCylinder(const Eigen::Isometry3d& X_WS, double r, double half_length,
                   const Eigen::Vector3d& o, const Eigen::Vector3d& d, double t_min) {
  const Eigen::Isometry3d X_SW = X_WS.inverse();
  const Eigen::Vector3d os = X_SW * o, ds = X_SW.linear() * d;
  double best = kInf;
  const double a = ds.head<2>().squaredNorm(), b = os.head<2>().dot(ds.head<2>()),
               c = os.head<2>().squaredNorm() - r * r;
  const double disc = b * b - a * c;
  if (a > 0 && disc >= 0) {
    for (double t : {(-b - std::sqrt(disc)) / a, (-b + std::sqrt(disc)) / a})
      if (t >= t_min && std::abs(os.z() + t * ds.z()) <= half_length) best = std::min(best, t);
  }
  if (ds.z() != 0) {
    for (double z : {-half_length, half_length}) {
      const double t = (z - os.z()) / ds.z();
      if (t >= t_min && (os + t * ds).head<2>().squaredNorm() <= r * r) best = std::min(best, t);
    }
  }
  return best;
}

double refSphere(const Eigen::Vector3d& c, double r, const Eigen::Vector3d& o,
                 const Eigen::Vector3d& d, double t_min) {
  const Eigen::Vector3d oc = o - c;
  const double b = oc.dot(d), disc = b * b - (oc.squaredNorm() - r * r);
  if (disc < 0) return kInf;
  for (double t : {-b - std::sqrt(disc), -b + std::sqrt(disc)})
    if (t >= t_min) return t;
  return kInf;
}

/// Exact first hit at t >= t_min over the scene's boxes, cylinders and spheres (meshes are unit
/// cubes: boxes).
double reference(const Scene& scene, const Eigen::Vector3d& o, const Eigen::Vector3d& d,
                 double t_min) {
  double best = kInf;
  for (const SceneItem& it : scene.items) {
    if (!it.collision) continue;
    const Eigen::Isometry3d X = scene.bodies[it.body].X_WB * it.X_BS;
    switch (it.shape.type) {
      case ShapeType::kBox:
        best = std::min(best, refBox(X, it.shape.size / 2, o, d, t_min));
        break;
      case ShapeType::kMesh:
        best = std::min(best, refBox(X, it.shape.scale / 2, o, d, t_min));
        break;
      case ShapeType::kCylinder:
        best = std::min(best, refCylinder(X, it.shape.radius, it.shape.length / 2, o, d, t_min));
        break;
      case ShapeType::kSphere:
        best = std::min(best, refSphere(X.translation(), it.shape.radius, o, d, t_min));
        break;
      default:
        ADD_FAILURE() << "no reference for this shape";
    }
  }
  return best;
}

/// The range model without noise applied to a true range.
double expected(const RaySensorConfig& c, double r) {
  if (r >= c.range_max) return kInf;
  if (r <= c.range_min) return -kInf;
  return r;
}

void expectScanMatchesReference(const Scene& scene, const Eigen::Isometry3d& X_WS,
                                const RaySensorConfig& c, const std::vector<float>& ranges,
                                double tol) {
  ASSERT_EQ(ranges.size(), static_cast<size_t>(c.samples));
  for (int i = 0; i < c.samples; ++i) {
    const double a = c.angle(i);
    const Eigen::Vector3d d = X_WS.linear() * Eigen::Vector3d(std::cos(a), std::sin(a), 0.0);
    const double want = expected(c, reference(scene, X_WS.translation(), d, c.range_min));
    if (std::isinf(want)) {
      EXPECT_EQ(ranges[i], want) << "beam " << i;
    } else {
      EXPECT_NEAR(ranges[i], want, tol) << "beam " << i << " angle " << a;
    }
  }
}

using Modes = std::tuple<PrimitiveMode, RayQueryMode>;

class RayCasterModes : public ::testing::TestWithParam<Modes> {
 protected:
  // Exact shapes: 1 mm (float rounding leaves ~1e-5). Tessellated cylinders: the polygon is
  // within max_sagitta radially, but a beam near tangency travels further along a chord, so
  // only centimetre accuracy there: one reason kAnalytic is the default.
  double tolerance() const {
    return std::get<0>(GetParam()) == PrimitiveMode::kTessellated ? 1e-2 : 1e-3;
  }
  RayCasterOptions options() const {
    RayCasterOptions o;
    o.primitives = std::get<0>(GetParam());
    o.query = std::get<1>(GetParam());
    return o;
  }
  // The seed hokuyo's scan of `scene` from X_WS, by a fresh caster in this mode.
  std::vector<float> seedScan(const Scene& scene, const Eigen::Isometry3d& X_WS) const {
    RayCaster caster(options());
    std::mt19937_64 rng(1);
    return scanRays(caster, scene, X_WS, seedHokuyo(), rng);
  }
};

// Square room 4 x 4 m around the sensor: beams 0, 360, 720 and 1080 point exactly at the
// corners (-135, -45, 45, 135 deg), where two walls meet.
TEST_P(RayCasterModes, SquareRoomEveryBeamIncludingCorners) {
  Scene scene;
  addRoom(scene, -2, 2, -2, 2);
  const RaySensorConfig c = seedHokuyo();
  const std::vector<float> r = seedScan(scene, pose(0, 0, 0.3));
  ASSERT_EQ(r.size(), 1081u);
  for (int i = 0; i < c.samples; ++i) {
    const double a = c.angle(i);
    const double want = 2.0 / std::max(std::abs(std::cos(a)), std::abs(std::sin(a)));
    ASSERT_NEAR(r[i], want, 1e-3) << "beam " << i;
    EXPECT_NEAR(r[i], want, 2e-5) << "beam " << i;  // float rounding only
  }
  for (int corner : {0, 360, 720, 1080}) EXPECT_NEAR(r[corner], 2 * std::sqrt(2.0), 1e-5);
  EXPECT_NEAR(r[540], 2.0, 1e-6);
}

// A level sensor whose rotation carries the 1e-17 rounding of a URDF chain (the seed's lidar
// at t = 0 in walled_room): its beams' z components are a few 1e-19, below Embree's 1e-18
// reciprocal floor, some of one sign and some of the other. Every beam still hits the room
// (ray_caster.cpp embreeComponent; once a whole packet of 16 beams came back +inf).
TEST_P(RayCasterModes, LevelSensorWithRoundingInItsRotationSeesEveryWall) {
  Scene scene;
  addRoom(scene, -3, 3, -2, 2);
  const RaySensorConfig c = seedHokuyo();
  Eigen::Isometry3d X_WS = pose(0.0936, -8.3e-5, 0.1457);
  X_WS.linear() << 1, 4.79421e-19, -1.73472e-18,  //
      5.64124e-19, 1, -1.69136e-17,               //
      3.46945e-18, -1.65087e-17, 1;
  const std::vector<float> r = seedScan(scene, X_WS);
  expectScanMatchesReference(scene, X_WS, c, r, tolerance());
}

// A rectangular room with rotated boxes, a cylinder and a mesh, seen from a generic pose.
TEST_P(RayCasterModes, ClutteredRoomMatchesExactGeometry) {
  Scene scene;
  addRoom(scene, -3, 2.5, -1.7, 2.2);
  const int b = addStatic(scene, "clutter");
  scene.bodies[b].X_WB = pose(0.2, -0.1, 0, 0.1);
  scene.items.push_back(boxItem(b, pose(1.2, 0.4, 0.5, 0.7), {0.3, 0.5, 1.0}));
  scene.items.push_back(boxItem(b, pose(-1.0, -1.0, 0.5, -0.3), {0.6, 0.2, 1.0}));
  scene.items.push_back(cylinderItem(b, pose(-0.8, 1.1, 0.5), 0.25, 1.0));
  scene.items.push_back(cylinderItem(b, pose(0.9, -0.9, 0.5), 0.05, 1.0));
  SceneItem cube = boxItem(b, pose(-2.0, 0.3, 0.5, 0.4), Eigen::Vector3d::Zero());
  cube.shape.type = ShapeType::kMesh;
  cube.shape.mesh_path = kCube;
  cube.shape.scale = Eigen::Vector3d(0.4, 0.7, 1.0);
  scene.items.push_back(cube);
  SceneItem visual_only = boxItem(b, pose(0.6, 0.0, 0.5), {0.1, 0.1, 1.0});
  visual_only.collision = false;
  visual_only.visual = true;
  scene.items.push_back(visual_only);  // rays must pass through it

  RayCaster caster(options());
  const RaySensorConfig c = seedHokuyo();
  std::mt19937_64 rng(1);
  for (const Eigen::Isometry3d& X_WS :
       {pose(0.13, -0.07, 0.3, 0.37), pose(-1.4, 1.5, 0.6, -2.2), pose(1.8, -1.2, 0.2, 2.9)}) {
    const std::vector<float> r = scanRays(caster, scene, X_WS, c, rng);
    expectScanMatchesReference(scene, X_WS, c, r, tolerance());
  }
}

// Beams that graze convex corners: beam 540 (0 deg) threads a 0.2 mm gap between two boxes
// whose corners sit 0.1 mm either side of it; beam 541 hits the upper box's front face.
TEST_P(RayCasterModes, GrazingConvexCorners) {
  Scene scene;
  addRoom(scene, -3, 3, -3, 3);
  const int b = addStatic(scene, "gap");
  const double delta = 1e-4;
  scene.items.push_back(boxItem(b, pose(1.2, delta + 0.25, 0.5), {0.4, 0.5, 1.0}));
  scene.items.push_back(boxItem(b, pose(1.2, -delta - 0.25, 0.5), {0.4, 0.5, 1.0}));
  const RaySensorConfig c = seedHokuyo();
  const Eigen::Isometry3d X_WS = pose(0, 0, 0.5);
  const std::vector<float> r = seedScan(scene, X_WS);
  EXPECT_NEAR(r[540], 3.0, 1e-5);
  EXPECT_NEAR(r[541], 1.0 / std::cos(c.angle(541)), 1e-5);
  EXPECT_NEAR(r[539], 1.0 / std::cos(c.angle(539)), 1e-5);
  expectScanMatchesReference(scene, X_WS, c, r, 1e-3);
}

// Gazebo's rays start at <range><min> (gazebo-classic physics/MultiRayShape.cc) and report
// min + the distance along the ray, i.e. the distance from the sensor origin. A lidar inside a
// housing smaller than range_min (0.1 m) -- an 8 cm box, a cylinder of radius 6 cm, a sphere of
// radius 7 cm, a 9 cm mesh cube, on a robot's link or static -- sees the room's walls through it.
TEST_P(RayCasterModes, RaysStartAtRangeMinThroughAHousing) {
  const RaySensorConfig c = seedHokuyo();
  const Eigen::Isometry3d X_WS = pose(0.3, -0.2, 0.5, 0.4);
  for (int kind = 0; kind < 4; ++kind) {
    for (bool moving : {true, false}) {
      Scene scene;
      addRoom(scene, -2, 2, -2, 2);
      SceneBody lidar;
      lidar.name = "robot::lidar_link";
      lidar.model = "robot";
      lidar.is_static = !moving;
      lidar.X_WB = X_WS;
      const int b = scene.addBody(lidar);
      const Eigen::Isometry3d X_BS = pose(0.005, -0.01, 0.02, 0.3);  // off-centre, turned
      if (kind == 0) scene.items.push_back(boxItem(b, X_BS, {0.08, 0.08, 0.08}));
      if (kind == 1) scene.items.push_back(cylinderItem(b, X_BS, 0.06, 0.1));
      if (kind == 2) scene.items.push_back(sphereItem(b, X_BS, 0.07));
      if (kind == 3) {
        SceneItem cube = boxItem(b, X_BS, Eigen::Vector3d::Zero());
        cube.shape.type = ShapeType::kMesh;
        cube.shape.mesh_path = kCube;
        cube.shape.scale = Eigen::Vector3d(0.09, 0.09, 0.09);
        scene.items.push_back(cube);
      }
      RayCaster caster(options());
      std::mt19937_64 rng(1);
      const std::vector<float> r = scanRays(caster, scene, X_WS, c, rng);
      for (int i = 0; i < c.samples; ++i) {
        const double a = c.angle(i) + 0.4;
        const double dx = std::cos(a), dy = std::sin(a);
        const double want = std::min(dx > 0 ? (2.0 - 0.3) / dx : (-2.0 - 0.3) / dx,
                                     dy > 0 ? (2.0 + 0.2) / dy : (-2.0 + 0.2) / dy);
        ASSERT_NEAR(r[i], want, 2e-5) << "housing " << kind << " moving " << moving << " beam " << i;
      }
      expectScanMatchesReference(scene, X_WS, c, r, 1e-3);
    }
  }
}

// Only what lies wholly nearer than range_min is unseen: a 2 mm plate ending 1 mm short of
// range_min is not seen, one starting 1 mm beyond it is (at its distance from the sensor), and
// one across it is seen from inside, at its far face (ODE's ray-box collider: a ray that starts
// inside a box hits the face it leaves by).
TEST_P(RayCasterModes, ObjectJustInsideRangeMinIsNotSeenJustOutsideIs) {
  const RaySensorConfig c = seedHokuyo();  // range_min 0.1
  for (const auto& [near_face, far_face, want] :
       {std::tuple<double, double, double>{0.097, 0.099, 3.0}, {0.101, 0.103, 0.101},
        {0.095, 0.105, 0.105}}) {
    Scene scene;
    addRoom(scene, -3, 3, -3, 3);
    const int b = addStatic(scene, "plate");
    scene.items.push_back(boxItem(b, pose((near_face + far_face) / 2, 0, 0.5),
                                  {far_face - near_face, 0.4, 1.0}));
    RayCaster caster(options());
    std::mt19937_64 rng(1);
    const std::vector<float> r = scanRays(caster, scene, pose(0, 0, 0.5), c, rng);
    EXPECT_NEAR(r[540], want, 1e-6) << "plate from " << near_face << " to " << far_face;
    expectScanMatchesReference(scene, pose(0, 0, 0.5), c, r, 1e-3);
  }
}

// A housing that reaches past range_min is seen from inside, as in Gazebo: a 30 cm cube
// around the sensor reads its far faces (0.15 m ahead) on every beam.
TEST_P(RayCasterModes, HousingBeyondRangeMinIsSeenFromInside) {
  Scene scene;
  addRoom(scene, -2, 2, -2, 2);
  const int b = addStatic(scene, "box");
  scene.items.push_back(boxItem(b, pose(0, 0, 0.5), {0.3, 0.3, 0.3}));
  const RaySensorConfig c = seedHokuyo();
  const std::vector<float> r = seedScan(scene, pose(0, 0, 0.5));
  for (int i = 0; i < c.samples; ++i) {
    const double a = c.angle(i);
    ASSERT_NEAR(r[i], 0.15 / std::max(std::abs(std::cos(a)), std::abs(std::sin(a))), 1e-5)
        << "beam " << i;
  }
}

// Embree picks its kernels by the CPU's ISA at run time, and their hit distances differed in
// the last bits (a scan recorded on an AVX-512 machine was not the one replayed on an AVX2
// one). Each hit's distance is now computed again by one scalar routine: the scans are the same
// bits whatever ISA Embree is forced to, for boxes, analytic and tessellated shapes, meshes,
// static and moving bodies.
TEST_P(RayCasterModes, SameBitsWhicheverIsaEmbreeUses) {
  Scene scene;
  addRoom(scene, -3, 2.5, -1.7, 2.2);
  const int b = addStatic(scene, "clutter");
  scene.bodies[b].X_WB = pose(0.2, -0.1, 0, 0.1);
  scene.items.push_back(boxItem(b, pose(1.2, 0.4, 0.5, 0.7), {0.3, 0.5, 1.0}));
  scene.items.push_back(cylinderItem(b, pose(-0.8, 1.1, 0.5), 0.25, 1.0));
  scene.items.push_back(sphereItem(b, pose(0.9, -0.9, 0.5), 0.3));
  SceneItem cube = boxItem(b, pose(-2.0, 0.3, 0.5, 0.4), Eigen::Vector3d::Zero());
  cube.shape.type = ShapeType::kMesh;
  cube.shape.mesh_path = kCube;
  cube.shape.scale = Eigen::Vector3d(0.4, 0.7, 1.0);
  scene.items.push_back(cube);
  SceneBody moving;
  moving.name = "cart::link";
  moving.model = "cart";
  moving.is_static = false;
  moving.X_WB = pose(0.4, 1.3, 0.0, 0.8);
  const int m = scene.addBody(moving);
  scene.items.push_back(boxItem(m, pose(0.0, 0.0, 0.4), {0.5, 0.3, 0.8}));
  scene.items.push_back(cylinderItem(m, pose(0.5, 0.0, 0.4), 0.1, 0.8));

  std::vector<std::string> isas = {"threads=1,isa=sse2", "threads=1,isa=sse4.2",
                                   "threads=1,isa=avx", ""};  // "": Embree's own defaults
  if (__builtin_cpu_supports("avx2")) isas.push_back("threads=1,isa=avx2");
  if (__builtin_cpu_supports("avx512f")) isas.push_back("threads=1,isa=avx512");
  const RaySensorConfig c = seedHokuyo();
  auto scans = [&](const std::string& config) {
    RayCasterOptions o = options();
    o.embree_config = config;
    RayCaster caster(o);
    std::vector<float> all;
    for (const Eigen::Isometry3d& X_WS :
         {pose(0.13, -0.07, 0.3, 0.37), pose(-1.4, 1.5, 0.6, -2.2), pose(1.8, -1.2, 0.2, 2.9)}) {
      std::mt19937_64 rng(1);
      const std::vector<float> r = scanRays(caster, scene, X_WS, c, rng);
      all.insert(all.end(), r.begin(), r.end());
    }
    return all;
  };
  const std::vector<float> best = scans(RayCasterOptions().embree_config);
  std::size_t hits = 0;
  for (float r : best) hits += std::isfinite(r);
  EXPECT_GT(hits, best.size() / 2);
  for (const std::string& isa : isas) {
    const std::vector<float> forced = scans(isa);
    ASSERT_EQ(forced.size(), best.size());
    std::size_t differ = 0;
    for (std::size_t i = 0; i < best.size(); ++i)
      differ += std::memcmp(&forced[i], &best[i], sizeof(float)) != 0;
    EXPECT_EQ(differ, 0u) << isa << ": " << differ << " of " << best.size() << " ranges differ";
  }
}

INSTANTIATE_TEST_SUITE_P(
    AllModes, RayCasterModes,
    ::testing::Combine(::testing::Values(PrimitiveMode::kHybrid, PrimitiveMode::kAnalytic,
                                         PrimitiveMode::kTessellated),
                       ::testing::Values(RayQueryMode::kSingle, RayQueryMode::kPacket16,
                                         RayQueryMode::kStream)),
    [](const ::testing::TestParamInfo<Modes>& info) {
      const PrimitiveMode mode = std::get<0>(info.param);
      const char* p = mode == PrimitiveMode::kHybrid     ? "Hybrid"
                      : mode == PrimitiveMode::kAnalytic ? "Analytic"
                                                         : "Tessellated";
      const RayQueryMode q = std::get<1>(info.param);
      const char* m = q == RayQueryMode::kSingle ? "Single" : q == RayQueryMode::kPacket16 ? "Packet16" : "Stream";
      return std::string(p) + m;
    });

TEST(RayCaster, RangeLimitsMapToInfinity) {
  Scene scene;
  addRoom(scene, -2, 2, -2, 2);
  SeedLidar lidar;
  // 5 cm from the east wall (10 cm thick): beam 540 (0 deg) starts at range_min inside the
  // wall and reads its outer face, 15 cm away (what Gazebo's rays do).
  std::vector<float> r = lidar.scan(scene, pose(1.95, 0, 0.5));
  EXPECT_NEAR(r[540], 0.15, 1e-5);
  EXPECT_NEAR(r[1080], 2.0 * std::sqrt(2.0), 1.0);  // other beams are finite
  EXPECT_TRUE(std::isfinite(r[1080]));
  // range_max 1.5 in a 4 m room: every beam from the centre is out of range.
  lidar.c.range_max = 1.5;
  r = lidar.scan(scene, pose(0, 0, 0.5));
  for (float v : r) EXPECT_EQ(v, std::numeric_limits<float>::infinity());
  // Just inside range_max is kept.
  lidar.c.range_max = 2.001;
  r = lidar.scan(scene, pose(0, 0, 0.5));
  EXPECT_NEAR(r[540], 2.0, 1e-5);
  // An empty scene: nothing to hit.
  Scene empty;
  RayCaster empty_caster;
  r = scanRays(empty_caster, empty, pose(0, 0, 0.5), seedHokuyo(), lidar.rng);
  for (float v : r) EXPECT_EQ(v, std::numeric_limits<float>::infinity());
}

// A sensor teleported to 1e30 (set_model_state) or NaN: Embree would abort on such a ray origin;
// the caster reports no hit instead.
TEST(RayCaster, SensorFarOutsideTheWorldSeesNothing) {
  Scene scene;
  addRoom(scene, -2, 2, -2, 2);
  SeedLidar lidar;
  for (double x : {1e30, -1e30, 1e19, 1e15, 1e12, 2.1e9, std::numeric_limits<double>::quiet_NaN(), kInf}) {
    const std::vector<float> r = lidar.scan(scene, pose(x, 0, 0.5));
    for (float v : r) EXPECT_EQ(v, std::numeric_limits<float>::infinity()) << x;
  }
  EXPECT_NEAR(lidar.scan(scene, pose(0, 0, 0.5))[540], 2.0, 0.05);  // still works
}

// The 6 m room of addRoom with a moving crate ("crate::link") at (1, 0, 0.5): its 0.4 x 0.5 x
// 1 m box at X_BG in the body. Returns the crate's body index.
static int addRoomWithCrate(Scene& scene, const Eigen::Isometry3d& X_BG) {
  addRoom(scene, -3, 3, -3, 3);
  SceneBody crate;
  crate.name = "crate::link";
  crate.model = "crate";
  crate.is_static = false;
  crate.X_WB = pose(1.0, 0, 0.5);
  const int b = scene.addBody(crate);
  scene.items.push_back(boxItem(b, X_BG, {0.4, 0.5, 1.0}));
  return b;
}

// A body at 1e30 or NaN at run time (a body flung by the physics; spawn, set_model_state and
// set_link_state refuse such poses): its pose would reach Embree as an instance transform or as
// the static scene's vertices (Embree aborts near 2e9 m, issue 43). The caster leaves such a body
// out of the scene (it is out of any sensor's reach) until it comes back.
TEST(RayCaster, MovingBodyFarOutsideTheWorldIsLeftOut) {
  Scene scene;
  const int b = addRoomWithCrate(scene, pose(0.1, 0, 0));
  Scene room;  // the same room without the crate
  addRoom(room, -3, 3, -3, 3);
  SeedLidar alone;
  const std::vector<float> expected = alone.scan(room, pose(0, 0, 0.5));
  SeedLidar lidar;
  EXPECT_NEAR(lidar.scan(scene, pose(0, 0, 0.5))[540], 0.9, 1e-5);
  for (double x : {1e30, -1e30, 2.1e9, 1e7, std::numeric_limits<double>::quiet_NaN(), kInf}) {
    scene.bodies[b].X_WB = pose(x, 0, 0.5);
    const std::vector<float> r = lidar.scan(scene, pose(0, 0, 0.5));
    EXPECT_NEAR(r[540], 3.0, 1e-5) << x;  // the wall behind, where the crate was
    EXPECT_EQ(lidar.caster.leftOutBodyCount(), std::abs(x) > 1e9 || !std::isfinite(x) ? 1u : 0u) << x;
    ASSERT_EQ(r.size(), expected.size());
    for (std::size_t i = 0; i < r.size(); ++i) EXPECT_NEAR(r[i], expected[i], 1e-5) << x << " beam " << i;
  }
  scene.bodies[b].X_WB = pose(1.0, 0, 0.5);  // back: seen again
  EXPECT_NEAR(lidar.scan(scene, pose(0, 0, 0.5))[540], 0.9, 1e-5);
  EXPECT_EQ(lidar.caster.leftOutBodyCount(), 0u);
  // A body that starts out there (the scene built with it), then comes back.
  RayCaster fresh;
  scene.bodies[b].X_WB = pose(1e30, 0, 0.5);
  std::vector<float> r = scanRays(fresh, scene, pose(0, 0, 0.5), seedHokuyo(), lidar.rng);
  EXPECT_NEAR(r[540], 3.0, 1e-5);
  EXPECT_EQ(fresh.leftOutBodyCount(), 1u);
  scene.bodies[b].X_WB = pose(2.0, 0, 0.5);
  r = scanRays(fresh, scene, pose(0, 0, 0.5), seedHokuyo(), lidar.rng);
  EXPECT_NEAR(r[540], 1.9, 1e-5);
  EXPECT_EQ(fresh.leftOutBodyCount(), 0u);
  // A static body moved there (its geometry is baked into the static part of the scene).
  scene.bodies[b].is_static = true;
  for (double x : {1e30, 2.1e9, std::numeric_limits<double>::quiet_NaN(), 1.0}) {
    scene.bodies[b].X_WB = pose(x, 0, 0.5);
    r = lidar.scan(scene, pose(0, 0, 0.5));
    EXPECT_NEAR(r[540], x == 1.0 ? 0.9 : 3.0, 1e-5) << x;
    EXPECT_EQ(lidar.caster.leftOutBodyCount(), x == 1.0 ? 0u : 1u) << x;
  }
}

// REP 117's masks, as Gazebo's RaySensor applies them to min + the distance along the ray:
// at or below range_min -inf, at or beyond range_max (no hit) +inf.
TEST(RayCaster, RangeModelMasksTheLimitsToInfinity) {
  const RaySensorConfig c = seedHokuyo();
  std::mt19937_64 rng(3);
  const float inf = std::numeric_limits<float>::infinity();
  std::vector<float> r = {0.0f, 0.0999f, 0.1001f, 5.0f, 9.999f, 10.0f, inf};
  applyRangeModel(c, rng, r.data(), static_cast<int>(r.size()));
  EXPECT_EQ(r, (std::vector<float>{-inf, -inf, 0.1001f, 5.0f, 9.999f, inf, inf}));
}

TEST(RayCaster, RangeModelClampsNoise) {
  const RaySensorConfig c = noisyHokuyo(0.0, 1.0);  // huge: values near the limits get clamped
  std::mt19937_64 rng(3);
  std::vector<float> r(2000);
  for (size_t i = 0; i < r.size(); ++i) r[i] = i % 2 ? 0.15f : 9.9f;
  applyRangeModel(c, rng, r.data(), static_cast<int>(r.size()));
  int at_min = 0, at_max = 0;
  for (float v : r) {
    EXPECT_GE(v, 0.1f);
    EXPECT_LE(v, 10.0f);
    at_min += v == static_cast<float>(c.range_min);
    at_max += v == static_cast<float>(c.range_max);
  }
  EXPECT_GT(at_min, 300);
  EXPECT_GT(at_max, 300);
}

TEST(RayCaster, NoiseMeanAndStddevOver1000Scans) {
  Scene scene;
  addRoom(scene, -2, 2, -2, 2);
  RayCaster caster;
  RaySensorConfig c = noisyHokuyo(0.02, 0.01);
  c.seed = 42;
  RaySensor sensor(c);
  double sum = 0, sum2 = 0;
  long n = 0;
  for (int scan = 0; scan < 1000; ++scan) {
    const std::vector<float>& r = sensor.scan(caster, scene, pose(0, 0, 0.5));
    for (int i = 0; i < c.samples; ++i) {
      const double a = c.angle(i);
      const double e = r[i] - 2.0 / std::max(std::abs(std::cos(a)), std::abs(std::sin(a)));
      sum += e;
      sum2 += e * e;
      ++n;
    }
  }
  const double mean = sum / n, sd = std::sqrt(sum2 / n - mean * mean);
  EXPECT_NEAR(mean, 0.02, 0.002);
  EXPECT_NEAR(sd, 0.01, 0.001);
}

TEST(RayCaster, SameSeedSameScansDifferentSeedDifferent) {
  Scene scene;
  addRoom(scene, -2, 2, -2, 2);
  RayCaster caster;
  RaySensorConfig c = noisyHokuyo(0.0, 0.01);
  auto scans = [&](std::uint64_t seed) {
    c.seed = seed;
    RaySensor sensor(c);
    std::vector<std::vector<float>> out;
    for (int k = 0; k < 5; ++k) out.push_back(sensor.scan(caster, scene, pose(0.1 * k, 0, 0.5)));
    return out;
  };
  const auto a = scans(7), b = scans(7), d = scans(8);
  EXPECT_EQ(a, b);
  EXPECT_NE(a, d);
  // Scans within one run differ (the generator advances).
  EXPECT_NE(a[0], scans(7)[1]);
}

TEST(RayCaster, MovingBodyIsSeenByTheNextScan) {
  Scene scene;
  const int b = addRoomWithCrate(scene, pose(0.1, 0, 0));  // the box offset in the body

  SeedLidar lidar;
  std::vector<float> r = lidar.scan(scene, pose(0, 0, 0.5));
  EXPECT_EQ(lidar.caster.movingBodyCount(), 1u);
  EXPECT_NEAR(r[540], 0.9, 1e-5);
  scene.bodies[b].X_WB = pose(2.0, 0, 0.5);
  r = lidar.scan(scene, pose(0, 0, 0.5));
  EXPECT_NEAR(r[540], 1.9, 1e-5);
  scene.bodies[b].X_WB = pose(1.0, 0, 0.5, M_PI / 2);  // turned: 0.5 deep, centre (1.0, 0.1)
  r = lidar.scan(scene, pose(0, 0, 0.5));
  EXPECT_NEAR(r[540], 0.75, 1e-5);
  scene.bodies[b].X_WB = pose(1.0, 2.0, 0.5);  // out of the beam: the wall again
  r = lidar.scan(scene, pose(0, 0, 0.5));
  EXPECT_NEAR(r[540], 3.0, 1e-5);
  expectScanMatchesReference(scene, pose(0, 0, 0.5), lidar.c, r, 1e-3);
}

// CPU seconds of this process's threads other than the calling one (/proc/self/task/*/stat).
static double otherThreadsCpuSeconds() {
  const std::string self = std::to_string(static_cast<long>(syscall(SYS_gettid)));
  double ticks = 0.0;
  for (const auto& task : std::filesystem::directory_iterator("/proc/self/task")) {
    if (task.path().filename() == self) continue;
    std::ifstream f(task.path() / "stat");
    const std::string stat((std::istreambuf_iterator<char>(f)), std::istreambuf_iterator<char>());
    const auto close = stat.rfind(')');
    if (close == std::string::npos) continue;  // the thread ended meanwhile
    std::istringstream fields(stat.substr(close + 2));  // from field 3, the state
    std::string skip;
    for (int k = 3; k < 14; ++k) fields >> skip;
    double utime = 0.0, stime = 0.0;
    fields >> utime >> stime;  // fields 14 and 15, in clock ticks
    ticks += utime + stime;
  }
  return ticks / static_cast<double>(sysconf(_SC_CLK_TCK));
}

static double thisThreadCpuSeconds() {
  timespec t{};
  clock_gettime(CLOCK_THREAD_CPUTIME_ID, &t);
  return static_cast<double>(t.tv_sec) + 1e-9 * static_cast<double>(t.tv_nsec);
}

TEST(RayCaster, ByDefaultEveryCommitAndCastRunsOnTheCallingThread) {
  // With Embree's own defaults its builds go to TBB workers on every hardware thread, and after
  // each commit of the moved bodies a worker spun in sched_yield: 85 us of another thread's CPU
  // per gym env step, 7 % of it. The default configuration ("threads=1") keeps the work on the
  // caller. A moving crate makes every scan commit the scene again.
  EXPECT_EQ(RayCasterOptions().embree_config, "threads=1");
  Scene scene;
  const int b = addRoomWithCrate(scene, pose(0, 0, 0));
  SeedLidar lidar;
  const double others0 = otherThreadsCpuSeconds(), self0 = thisThreadCpuSeconds();
  std::vector<float> r;
  for (int k = 0; k < 1500; ++k) {
    scene.bodies[b].X_WB = pose(1.0 + 0.001 * (k % 100), 0, 0.5);
    r = lidar.scan(scene, pose(0, 0, 0.5));
  }
  const double others = otherThreadsCpuSeconds() - others0, self = thisThreadCpuSeconds() - self0;
  EXPECT_NEAR(r[540], 1.0 + 0.001 * 99 - 0.2, 1e-5);  // the last pose was seen
  EXPECT_GT(self, 0.05);
  EXPECT_LT(others, 0.1 * self) << "1500 scans: " << self << " s of CPU on the calling thread, "
                                << others << " s on the process's other threads";
}

TEST(RayCaster, SensorSeesPastItsOwnHousingAndSeesAnotherOne) {
  // Two lidars in housings (0.1 m cubes, their faces 5 cm from the sensor: within range_min)
  // 1 m apart in a 6 m room: each sees the other's housing and the walls past its own. Its
  // own link is not special: a part of it beyond range_min is seen, as in Gazebo, whose rays
  // test every collision of the world (physics/ode/ODEMultiRayShape.cc, UpdateCallback).
  Scene scene;
  addRoom(scene, -3, 3, -3, 3);
  int housing[2];
  for (int k = 0; k < 2; ++k) {
    SceneBody b;
    b.name = "car_" + std::to_string(k) + "::lidar";
    b.model = "car_" + std::to_string(k);
    b.is_static = false;
    b.X_WB = pose(k, 0, 0.5);
    housing[k] = scene.addBody(b);
    scene.items.push_back(boxItem(housing[k], pose(0, 0, 0), {0.1, 0.1, 0.1}));
  }
  SeedLidar lidar;  // beam 540 along +x, 180 at -90 deg
  const RaySensorConfig& c = lidar.c;
  std::vector<float> r = lidar.scan(scene, pose(0, 0, 0.5));
  EXPECT_NEAR(r[540], expected(c, 0.95), 1e-5);  // the other housing's near face
  EXPECT_NEAR(r[180], expected(c, 3.0), 1e-5);   // -90 deg: the room's wall
  r = lidar.scan(scene, pose(1, 0, 0.5, M_PI));
  EXPECT_NEAR(r[540], expected(c, 0.95), 1e-5);
  // A bracket of car 0's own lidar link, 0.4 m to its right: seen.
  scene.items.push_back(boxItem(housing[0], pose(0, -0.45, 0), {0.1, 0.1, 0.1}));
  r = lidar.scan(scene, pose(0, 0, 0.5));
  EXPECT_NEAR(r[180], expected(c, 0.4), 1e-5);
  EXPECT_NEAR(r[540], expected(c, 0.95), 1e-5);
}

TEST(RayCaster, SceneChangesAreRebuiltAndStaticBodiesRead) {
  Scene scene;
  addRoom(scene, -3, 3, -3, 3);
  SeedLidar lidar;
  EXPECT_NEAR(lidar.scan(scene, pose(0, 0, 0.5))[540], 3.0, 1e-5);
  const int b = addStatic(scene, "late");
  scene.items.push_back(boxItem(b, pose(1.5, 0, 0.5), {1.0, 1.0, 1.0}));
  EXPECT_NEAR(lidar.scan(scene, pose(0, 0, 0.5))[540], 1.0, 1e-5);
  scene.bodies[b].X_WB = pose(0.5, 0, 0);  // a static body moved (e.g. set_model_state)
  EXPECT_NEAR(lidar.scan(scene, pose(0, 0, 0.5))[540], 1.5, 1e-5);
}

TEST(RayCaster, AShapeThatChangesSizeOrIsSwappedForAnotherIsRebuilt) {
  // The counts of bodies and items stay the same: only the shapes change (a model deleted and
  // another spawned between two scans, a mesh's scale). Static and moving bodies alike.
  Scene scene;
  addRoom(scene, -3, 3, -3, 3);
  const int b = addStatic(scene, "crate");
  scene.items.push_back(boxItem(b, pose(1.5, 0, 0.5), {1.0, 1.0, 1.0}));
  SceneBody mover;
  mover.name = "ball::link";
  mover.model = "ball";
  mover.is_static = false;
  mover.X_WB = pose(-1.5, 0, 0.5);
  const int m = scene.addBody(mover);
  scene.items.push_back(boxItem(m, pose(0, 0, 0), {0.2, 0.2, 0.2}));
  const std::size_t crate = scene.items.size() - 2, ball = scene.items.size() - 1;
  SeedLidar lidar;  // beam 540 along +x, 0 along -x (almost: -135 deg is beam 0; use 900)
  std::vector<float> r = lidar.scan(scene, pose(0, 0, 0.5));
  EXPECT_NEAR(r[540], 1.0, 1e-5);
  scene.items[crate].shape.size = Eigen::Vector3d(2.0, 2.0, 1.0);  // the crate grows
  r = lidar.scan(scene, pose(0, 0, 0.5));
  EXPECT_NEAR(r[540], 0.5, 1e-5);
  // The moving ball grows, seen from the side (beam 180 looks along -y, so turn the sensor).
  const Eigen::Isometry3d back = pose(0, 0, 0.5, M_PI);
  EXPECT_NEAR(lidar.scan(scene, back)[540], 1.4, 1e-5);
  scene.items[ball].shape.size = Eigen::Vector3d(1.0, 1.0, 1.0);
  EXPECT_NEAR(lidar.scan(scene, back)[540], 1.0, 1e-5);
  // Swapped for a cylinder of radius 0.3 (same counts).
  scene.items[ball].shape.type = ShapeType::kCylinder;
  scene.items[ball].shape.radius = 0.3;
  scene.items[ball].shape.length = 1.0;
  EXPECT_NEAR(lidar.scan(scene, back)[540], 1.2, 1e-5);
  // An item no longer a collision (and a visual one made one): the ray caster follows.
  scene.items[crate].collision = false;
  EXPECT_NEAR(lidar.scan(scene, pose(0, 0, 0.5))[540], 3.0, 1e-5);
  scene.items[crate].collision = true;
  EXPECT_NEAR(lidar.scan(scene, pose(0, 0, 0.5))[540], 0.5, 1e-5);
  // Unchanged scenes do not rebuild: the moving body's pose still commits as before.
  scene.bodies[m].X_WB = pose(-2.0, 0, 0.5);
  EXPECT_NEAR(lidar.scan(scene, back)[540], 1.7, 1e-5);
}

TEST(RayCaster, GroundPlaneSphereAndTiltedSensor) {
  for (PrimitiveMode mode :
       {PrimitiveMode::kHybrid, PrimitiveMode::kAnalytic, PrimitiveMode::kTessellated}) {
    Scene scene;
    const int g = addStatic(scene, "ground_plane");
    SceneItem plane;
    plane.body = g;
    plane.shape.type = ShapeType::kPlane;
    plane.collision = true;
    scene.items.push_back(plane);
    const int s = addStatic(scene, "ball");
    SceneItem ball = boxItem(s, pose(0, 2.0, 0.5), Eigen::Vector3d::Zero());
    ball.shape.type = ShapeType::kSphere;
    ball.shape.radius = 0.5;
    scene.items.push_back(ball);
    RayCasterOptions o;
    o.primitives = mode;
    RayCaster caster(o);
    const RaySensorConfig c = seedHokuyo();
    std::mt19937_64 rng(1);
    // Pitched down 0.2 rad at 0.5 m: beam 540 meets the ground at 0.5 / sin(0.2).
    std::vector<float> r = scanRays(caster, scene, pose(0, 0, 0.5, 0.0, 0.2), c, rng);
    EXPECT_NEAR(r[540], 0.5 / std::sin(0.2), 1e-4);
    // A tilted plane (a ramp through x = 4, rising towards +x at 45 deg): the level beam at
    // 0 deg meets it at x = 4 + 0.5 -> 4.5 m. (Triangles at 1e4 m would be off here; kHybrid
    // keeps tilted planes analytic.)
    {
      Scene ramp_scene = scene;
      const int r = addStatic(ramp_scene, "ramp");
      SceneItem ramp = plane;
      ramp.body = r;
      ramp.X_BS = pose(4.0, 0, 0);
      ramp.shape.normal = Eigen::Vector3d(-1, 0, 1).normalized();
      ramp_scene.items.push_back(ramp);
      RayCaster ramp_caster(o);
      const std::vector<float> rr = scanRays(ramp_caster, ramp_scene, pose(0, 0, 0.5), c, rng);
      EXPECT_NEAR(rr[540], 4.5, mode == PrimitiveMode::kTessellated ? 2e-3 : 1e-5);
    }
    // Level at the ball's centre height: beam at +90 deg (index 900) hits it at 1.5 m.
    r = scanRays(caster, scene, pose(0, 0, 0.5), c, rng);
    EXPECT_NEAR(r[900], 1.5, mode == PrimitiveMode::kTessellated ? 1e-3 : 1e-5);
    EXPECT_EQ(r[540], std::numeric_limits<float>::infinity());
  }
}

TEST(RayCaster, MissingMeshNamesBodyAndPath) {
  Scene scene;
  const int b = addStatic(scene, "statue");
  SceneItem it = boxItem(b, Eigen::Isometry3d::Identity(), Eigen::Vector3d::Zero());
  it.shape.type = ShapeType::kMesh;
  it.shape.mesh_path = "/no/such/statue.stl";
  scene.items.push_back(it);
  RayCaster caster;
  try {
    caster.build(scene);
    FAIL() << "no error";
  } catch (const RayCasterError& e) {
    EXPECT_NE(std::string(e.what()).find("body 'statue::link'"), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("/no/such/statue.stl"), std::string::npos) << e.what();
  }
}

TEST(RaySensor, ScansFromLinkPoseTimesSensorPose) {
  Scene scene;
  addRoom(scene, -2, 2, -2, 2);
  RayCaster caster;
  RaySensorConfig c = seedHokuyo();
  c.X_LS = pose(0, 0, 0.0124);
  RaySensor sensor(c);
  // Link at (1, 0) yawed 90 deg: beam 540 looks along +y, 2 m to the wall; beam 0 (-135 deg
  // in the sensor) looks towards +x -y... at the south-east corner region.
  const std::vector<float>& r = sensor.scan(caster, scene, pose(1.0, 0, 0.3, M_PI / 2));
  EXPECT_NEAR(r[540], 2.0, 1e-5);
  EXPECT_NEAR(r[180], 1.0, 1e-5);  // -90 deg in the sensor = +x in the world
  EXPECT_NEAR(r[900], 3.0, 1e-5);  // +90 deg = -x
}

}  // namespace
}  // namespace tianracer_sim

int main(int argc, char** argv) {
  ::testing::InitGoogleTest(&argc, argv);
  return RUN_ALL_TESTS();
}
