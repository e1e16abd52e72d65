// Ray casting against the collision items of a Scene with Embree 3. ROS-free.
//
// Layout: one top-level RTCScene holding only instances. All static bodies' geometry goes, in
// world coordinates, into one sub-scene built once and instanced with the identity; each
// moving body's geometry goes, in body coordinates, into its own sub-scene whose instance
// transform is set from SceneBody::X_WB before a scan (rtcSetGeometryTransform, then
// rtcCommitScene of the top level, which only rebuilds a BVH over a handful of instances).
//
// Shapes (PrimitiveMode):
//  - kHybrid (default): whatever triangles represent exactly is triangles (boxes: 12; planes
//    whose normal is a world/body axis: 2 triangles of 1e4 m, exact because their vertices lie
//    exactly on the plane; meshes); cylinders, spheres and tilted planes are Embree user
//    geometry whose callbacks intersect the exact shape in double precision. Exact to float
//    rounding (~1e-6 m at 10 m) at about the speed of pure triangles (see bench/lidar_bench).
//  - kAnalytic: boxes too (and every plane) are user geometry: exact, ~2x slower than triangles.
//  - kTessellated: everything is triangles; cylinders and spheres are inscribed polygons within
//    `max_sagitta` radially, but near-tangent beams can be off by more (centimetres): fastest,
//    not exact.
// Meshes come through MeshCache::global(), scaled by Shape::scale.
#ifndef TIANRACER_SIM_LIDAR_RAY_CASTER_H
#define TIANRACER_SIM_LIDAR_RAY_CASTER_H

#include <cstddef>
#include <memory>
#include <stdexcept>
#include <string>
#include <vector>

#include <Eigen/Geometry>

#include "tianracer_sim/common/diagnostic.h"
#include "tianracer_sim/common/step_profile.h"
#include "tianracer_sim/scene/scene.h"

namespace tianracer_sim {

/// Embree failures and collision items that cannot be built (a mesh that does not load...).
using RayCasterError = InputError;

enum class PrimitiveMode { kHybrid, kAnalytic, kTessellated };

/// How rays are handed to Embree: a loop of rtcIntersect1, packets of 16 (rtcIntersect16),
/// or one stream (rtcIntersect1M).
enum class RayQueryMode { kSingle, kPacket16, kStream };

struct RayCasterOptions {
  PrimitiveMode primitives = PrimitiveMode::kHybrid;
  RayQueryMode query = RayQueryMode::kPacket16;
  double max_sagitta = 1e-4;  // m, tessellation error bound for cylinders and spheres
  /// Embree's device configuration (rtcNewDevice): comma-separated key=value, e.g.
  /// "threads=1,isa=sse2" to force one ISA (tests). The distances do not depend on it: each
  /// hit's distance is computed again by one scalar routine.
  /// The default builds on the calling thread only. The scene committed for each scan is a few
  /// instances; with Embree's default (TBB workers on every hardware thread) a worker spun in
  /// sched_yield after each commit: 85 us of another thread's CPU per gym env step (7 % of it),
  /// for no faster scan, and on 2 cores taken from the physics. "" = Embree's defaults.
  std::string embree_config = "threads=1";
};

/// Casts rays and nothing else: beam layout, range limits and noise belong to the sensor
/// (RaySensor). Not thread-safe: one caster per thread (each owns its Embree device and
/// scenes). A ray is the segment t in [t_min, t_max] of origin + t * direction: what lies
/// nearer than t_min is not seen, and distances are still measured from the origin.
class RayCaster {
 public:
  explicit RayCaster(RayCasterOptions options = {});
  ~RayCaster();
  RayCaster(const RayCaster&) = delete;
  RayCaster& operator=(const RayCaster&) = delete;

  const RayCasterOptions& options() const { return options_; }

  /// (Re)builds the acceleration structures from the scene's collision items. Called by
  /// update() when the number of bodies or items has changed since the last build, or any
  /// collision item's body, placement or shape (a size, a mesh, a scale) has.
  void build(const Scene& scene);
  /// Sets the moving bodies' transforms from the scene (commits only if one changed). Static
  /// bodies are read at build time only. Every body is seen, the sensor's own included, as by
  /// Gazebo's rays (a housing within range_min is passed because rays start there).
  void update(const Scene& scene);

  /// Distance from `origin_W` along each ray to the first collision surface with t in
  /// [t_min, t_max], or +inf. A ray that starts inside a solid (t_min inside it) hits the
  /// solid's far side, as ODE's ray colliders do. `directions` are unit vectors in the world
  /// frame, one result per direction. Call update() first so that moving bodies are where the
  /// scene says.
  void castRays(const Eigen::Vector3d& origin_W, const std::vector<Eigen::Vector3f>& directions,
                float t_min, float t_max, float* distances);

  /// Statistics of the last build.
  std::size_t triangleCount() const;
  std::size_t analyticCount() const;
  std::size_t movingBodyCount() const;
  /// Bodies left out of the scene by the last update() because their pose is not finite or is
  /// farther than kMaxBodyPosition (a body set or flung there at run time): such a pose never
  /// reaches Embree (it aborts near 2e9 m), and the body is out of any sensor's reach. A body
  /// that comes back is in the scene again.
  std::size_t leftOutBodyCount() const;
  static constexpr double kMaxBodyPosition = 1e9;  // m, each coordinate of a body's origin

  /// Times update()'s commits of moved bodies (and rebuilds) and castRays() into `profile`
  /// (common/step_profile.h), as parts of the sensors' sampling rows; null: not timed.
  void setProfile(StepProfile* profile);

 private:
  struct Impl;
  RayCasterOptions options_;
  std::unique_ptr<Impl> impl_;
  StepProfile* profile_ = nullptr;
  int update_row_ = -1, cast_row_ = -1;
};

}  // namespace tianracer_sim

#endif  // TIANRACER_SIM_LIDAR_RAY_CASTER_H
