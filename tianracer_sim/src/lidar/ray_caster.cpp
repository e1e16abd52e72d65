// Embree 3 ray casting against the Scene's collision items (see ray_caster.h for the layout).
#include "tianracer_sim/lidar/ray_caster.h"

#include <algorithm>
#include <cassert>
#include <cmath>
#include <cstring>
#include <limits>
#include <string>

#include <embree3/rtcore.h>

#include "tianracer_sim/mesh/mesh_loader.h"

namespace tianracer_sim {

namespace {

constexpr double kInf = std::numeric_limits<double>::infinity();
constexpr double kPlaneExtent = 1e4;   // m, half size of a tessellated plane
constexpr double kPlaneBounds = 1e5;   // m, bounds of an analytic plane

/// An exact primitive, in the frame P of its sub-scene (world for static bodies, body frame for
/// moving ones).
struct Analytic {
  ShapeType type = ShapeType::kBox;
  Eigen::Isometry3d X_PS = Eigen::Isometry3d::Identity();
  Eigen::Isometry3d X_SP = Eigen::Isometry3d::Identity();
  Eigen::Vector3d half = Eigen::Vector3d::Zero();  // box half extents
  double radius = 0.0;
  double half_length = 0.0;
  Eigen::Vector3d normal = Eigen::Vector3d::UnitZ();  // plane normal in S
};

// Smallest root of a t^2 + 2 b t + c = 0 in [tn, tf] (both roots tried), or false.
bool quadraticHit(double a, double b, double c, double tn, double tf, double* t) {
  if (a <= 0.0) return false;
  const double disc = b * b - a * c;
  if (disc < 0.0) return false;
  const double sq = std::sqrt(disc);
  const double t0 = (-b - sq) / a;
  const double t1 = (-b + sq) / a;
  if (t0 >= tn && t0 <= tf) {
    *t = t0;
    return true;
  }
  if (t1 >= tn && t1 <= tf) {
    *t = t1;
    return true;
  }
  return false;
}

// Ray (o, d) in the shape frame against the exact shape: the first surface point with
// t in [tn, tf]. From inside a solid that is its exit point, as for closed triangle meshes.
bool intersectShape(const Analytic& p, const Eigen::Vector3d& o, const Eigen::Vector3d& d,
                    double tn, double tf, double* t_hit, Eigen::Vector3d* n_hit) {
  switch (p.type) {
    case ShapeType::kBox: {
      double t_enter = -kInf, t_exit = kInf;
      int axis_enter = 0, axis_exit = 0;
      for (int k = 0; k < 3; ++k) {
        if (d[k] == 0.0) {
          if (std::abs(o[k]) > p.half[k]) return false;
          continue;
        }
        double a = (-p.half[k] - o[k]) / d[k];
        double b = (p.half[k] - o[k]) / d[k];
        if (a > b) std::swap(a, b);
        if (a > t_enter) t_enter = a, axis_enter = k;
        if (b < t_exit) t_exit = b, axis_exit = k;
      }
      if (t_enter > t_exit) return false;
      int axis;
      if (t_enter >= tn) {
        *t_hit = t_enter;
        axis = axis_enter;
      } else {
        *t_hit = t_exit;
        axis = axis_exit;
      }
      if (*t_hit < tn || *t_hit > tf) return false;
      *n_hit = Eigen::Vector3d::Zero();
      (*n_hit)[axis] = d[axis] > 0.0 ? -1.0 : 1.0;
      return true;
    }
    case ShapeType::kCylinder: {
      double best = kInf;
      Eigen::Vector3d n = Eigen::Vector3d::Zero();
      const double a = d.x() * d.x() + d.y() * d.y();
      const double b = o.x() * d.x() + o.y() * d.y();
      const double c = o.x() * o.x() + o.y() * o.y() - p.radius * p.radius;
      if (a > 0.0) {
        const double disc = b * b - a * c;
        if (disc >= 0.0) {
          const double sq = std::sqrt(disc);
          for (const double t : {(-b - sq) / a, (-b + sq) / a}) {
            if (t < tn || t > tf || t >= best) continue;
            const double z = o.z() + t * d.z();
            if (std::abs(z) > p.half_length) continue;
            best = t;
            n = Eigen::Vector3d(o.x() + t * d.x(), o.y() + t * d.y(), 0.0);
          }
        }
      }
      if (d.z() != 0.0) {
        for (const double zc : {-p.half_length, p.half_length}) {
          const double t = (zc - o.z()) / d.z();
          if (t < tn || t > tf || t >= best) continue;
          const double x = o.x() + t * d.x(), y = o.y() + t * d.y();
          if (x * x + y * y > p.radius * p.radius) continue;
          best = t;
          n = Eigen::Vector3d(0.0, 0.0, zc > 0.0 ? 1.0 : -1.0);
        }
      }
      if (best == kInf) return false;
      *t_hit = best;
      *n_hit = n;
      return true;
    }
    case ShapeType::kSphere: {
      double t;
      if (!quadraticHit(d.squaredNorm(), o.dot(d), o.squaredNorm() - p.radius * p.radius, tn, tf,
                        &t))
        return false;
      *t_hit = t;
      *n_hit = o + t * d;
      return true;
    }
    case ShapeType::kPlane: {
      const double den = p.normal.dot(d);
      if (den == 0.0) return false;
      const double t = -p.normal.dot(o) / den;
      if (t < tn || t > tf) return false;
      *t_hit = t;
      *n_hit = p.normal;
      return true;
    }
    case ShapeType::kMesh:
      return false;
  }
  return false;
}

void analyticBounds(const RTCBoundsFunctionArguments* args) {
  const auto& prims = *static_cast<const std::vector<Analytic>*>(args->geometryUserPtr);
  const Analytic& p = prims[args->primID];
  Eigen::AlignedBox3d box;
  if (p.type == ShapeType::kPlane) {
    box = Eigen::AlignedBox3d(Eigen::Vector3d::Constant(-kPlaneBounds),
                              Eigen::Vector3d::Constant(kPlaneBounds));
  } else {
    Eigen::Vector3d h = p.half;
    if (p.type == ShapeType::kCylinder) h = Eigen::Vector3d(p.radius, p.radius, p.half_length);
    if (p.type == ShapeType::kSphere) h = Eigen::Vector3d::Constant(p.radius);
    for (int i = 0; i < 8; ++i) {
      const Eigen::Vector3d corner((i & 1) ? h.x() : -h.x(), (i & 2) ? h.y() : -h.y(),
                                   (i & 4) ? h.z() : -h.z());
      box.extend(p.X_PS * corner);
    }
  }
  // Pad so that float rounding never clips the exact shape.
  const Eigen::Vector3d pad = box.max().cwiseAbs().cwiseMax(box.min().cwiseAbs()) * 1e-6 +
                              Eigen::Vector3d::Constant(1e-6);
  RTCBounds* b = args->bounds_o;
  b->lower_x = static_cast<float>(box.min().x() - pad.x());
  b->lower_y = static_cast<float>(box.min().y() - pad.y());
  b->lower_z = static_cast<float>(box.min().z() - pad.z());
  b->upper_x = static_cast<float>(box.max().x() + pad.x());
  b->upper_y = static_cast<float>(box.max().y() + pad.y());
  b->upper_z = static_cast<float>(box.max().z() + pad.z());
}

void analyticIntersect(const RTCIntersectFunctionNArguments* args) {
  const auto& prims = *static_cast<const std::vector<Analytic>*>(args->geometryUserPtr);
  const Analytic& p = prims[args->primID];
  const unsigned N = args->N;
  RTCRayN* rays = RTCRayHitN_RayN(args->rayhit, N);
  RTCHitN* hits = RTCRayHitN_HitN(args->rayhit, N);
  for (unsigned i = 0; i < N; ++i) {
    if (args->valid[i] != -1) continue;
    const Eigen::Vector3d o(RTCRayN_org_x(rays, N, i), RTCRayN_org_y(rays, N, i),
                            RTCRayN_org_z(rays, N, i));
    const Eigen::Vector3d d(RTCRayN_dir_x(rays, N, i), RTCRayN_dir_y(rays, N, i),
                            RTCRayN_dir_z(rays, N, i));
    double t;
    Eigen::Vector3d n_S;
    if (!intersectShape(p, p.X_SP * o, p.X_SP.linear() * d, RTCRayN_tnear(rays, N, i),
                        RTCRayN_tfar(rays, N, i), &t, &n_S))
      continue;
    RTCRayN_tfar(rays, N, i) = static_cast<float>(t);
    const Eigen::Vector3d n_P = p.X_PS.linear() * n_S;
    RTCHitN_Ng_x(hits, N, i) = static_cast<float>(n_P.x());
    RTCHitN_Ng_y(hits, N, i) = static_cast<float>(n_P.y());
    RTCHitN_Ng_z(hits, N, i) = static_cast<float>(n_P.z());
    RTCHitN_u(hits, N, i) = 0.0f;
    RTCHitN_v(hits, N, i) = 0.0f;
    RTCHitN_primID(hits, N, i) = args->primID;
    RTCHitN_geomID(hits, N, i) = args->geomID;
    RTCHitN_instID(hits, N, i, 0) = args->context->instID[0];
  }
}

void analyticOccluded(const RTCOccludedFunctionNArguments* args) {
  const auto& prims = *static_cast<const std::vector<Analytic>*>(args->geometryUserPtr);
  const Analytic& p = prims[args->primID];
  const unsigned N = args->N;
  for (unsigned i = 0; i < N; ++i) {
    if (args->valid[i] != -1) continue;
    const Eigen::Vector3d o(RTCRayN_org_x(args->ray, N, i), RTCRayN_org_y(args->ray, N, i),
                            RTCRayN_org_z(args->ray, N, i));
    const Eigen::Vector3d d(RTCRayN_dir_x(args->ray, N, i), RTCRayN_dir_y(args->ray, N, i),
                            RTCRayN_dir_z(args->ray, N, i));
    double t;
    Eigen::Vector3d n;
    if (intersectShape(p, p.X_SP * o, p.X_SP.linear() * d, RTCRayN_tnear(args->ray, N, i),
                       RTCRayN_tfar(args->ray, N, i), &t, &n))
      RTCRayN_tfar(args->ray, N, i) = -std::numeric_limits<float>::infinity();
  }
}

// A direction component as handed to Embree. Embree replaces |x| < 1e-18 by +1e-18 before
// taking reciprocals (zero_fix/rcp_safe, kernels/common/ray.h and common/math/vec3fa.h), which
// drops the sign of a tiny negative component, while its coherent packet and stream traversal
// picks one octant for the packet from the components' signs (bvh_intersector_stream.cpp,
// initPacketsAndFrustum). A packet with such a component then skips nodes it passes through:
// a level lidar at t = 0, its rotation carrying 1e-18 rounding from the URDF chain, lost a
// whole packet of 16 beams. Below 1e-12 (1e-8 m at 10 km) the component is made an exact +0.
inline float embreeComponent(double x) {
  return std::abs(x) < 1e-12 ? 0.0f : static_cast<float>(x);
}

/// One ray from o along d over [t_min, t_max], with no hit yet (single rays and streams).
void setUpRay(RTCRayHit* rh, const Eigen::Vector3f& o, const Eigen::Vector3f& d, float t_min,
              float t_max, int id) {
  rh->ray.org_x = o.x(), rh->ray.org_y = o.y(), rh->ray.org_z = o.z();
  rh->ray.dir_x = embreeComponent(d.x());
  rh->ray.dir_y = embreeComponent(d.y());
  rh->ray.dir_z = embreeComponent(d.z());
  rh->ray.tnear = t_min;
  rh->ray.tfar = t_max;
  rh->ray.time = 0.0f;
  rh->ray.mask = 0xFFFFFFFFu;
  rh->ray.id = id;
  rh->ray.flags = 0;
  rh->hit.geomID = RTC_INVALID_GEOMETRY_ID;
  rh->hit.instID[0] = RTC_INVALID_GEOMETRY_ID;
}

/// Triangles of one sub-scene, in its frame.
struct TriangleSoup {
  std::vector<float> vertices;  // xyz
  std::vector<uint32_t> indices;

  uint32_t addVertex(const Eigen::Vector3d& v) {
    vertices.push_back(static_cast<float>(v.x()));
    vertices.push_back(static_cast<float>(v.y()));
    vertices.push_back(static_cast<float>(v.z()));
    return static_cast<uint32_t>(vertices.size() / 3 - 1);
  }
  void addTriangle(uint32_t a, uint32_t b, uint32_t c) {
    indices.push_back(a);
    indices.push_back(b);
    indices.push_back(c);
  }
  std::size_t triangleCount() const { return indices.size() / 3; }
};

// Polygon with at most `sagitta` deviation from a circle of radius r.
int segmentsFor(double r, double sagitta) {
  if (r <= sagitta) return 8;
  const double n = M_PI / std::acos(1.0 - sagitta / r);
  return std::clamp(static_cast<int>(std::ceil(n)), 8, 4096);
}

void tessellate(const Shape& s, const Eigen::Isometry3d& X, double sagitta, TriangleSoup* out) {
  switch (s.type) {
    case ShapeType::kBox: {
      const Eigen::Vector3d h = s.size / 2;
      uint32_t v[8];
      for (int i = 0; i < 8; ++i)
        v[i] = out->addVertex(X * Eigen::Vector3d((i & 1) ? h.x() : -h.x(),
                                                  (i & 2) ? h.y() : -h.y(),
                                                  (i & 4) ? h.z() : -h.z()));
      // Faces as corner-index quads.
      const int faces[6][4] = {{0, 2, 6, 4}, {1, 5, 7, 3}, {0, 4, 5, 1},
                               {2, 3, 7, 6}, {0, 1, 3, 2}, {4, 6, 7, 5}};
      for (const auto& f : faces) {
        out->addTriangle(v[f[0]], v[f[1]], v[f[2]]);
        out->addTriangle(v[f[0]], v[f[2]], v[f[3]]);
      }
      break;
    }
    case ShapeType::kPlane: {
      const Eigen::Vector3d n = s.normal.normalized();
      const Eigen::Vector3d u = n.unitOrthogonal();
      const Eigen::Vector3d w = n.cross(u);
      const double L = kPlaneExtent;
      const uint32_t a = out->addVertex(X * (-L * u - L * w));
      const uint32_t b = out->addVertex(X * (L * u - L * w));
      const uint32_t c = out->addVertex(X * (L * u + L * w));
      const uint32_t d = out->addVertex(X * (-L * u + L * w));
      out->addTriangle(a, b, c);
      out->addTriangle(a, c, d);
      break;
    }
    case ShapeType::kCylinder: {
      const int n = segmentsFor(s.radius, sagitta);
      const double hl = s.length / 2;
      const uint32_t top = out->addVertex(X * Eigen::Vector3d(0, 0, hl));
      const uint32_t bottom = out->addVertex(X * Eigen::Vector3d(0, 0, -hl));
      const uint32_t first = static_cast<uint32_t>(out->vertices.size() / 3);
      for (int i = 0; i < n; ++i) {
        const double a = 2 * M_PI * i / n;
        const double x = s.radius * std::cos(a), y = s.radius * std::sin(a);
        out->addVertex(X * Eigen::Vector3d(x, y, -hl));
        out->addVertex(X * Eigen::Vector3d(x, y, hl));
      }
      for (int i = 0; i < n; ++i) {
        const uint32_t b0 = first + 2 * i, t0 = b0 + 1;
        const uint32_t b1 = first + 2 * ((i + 1) % n), t1 = b1 + 1;
        out->addTriangle(b0, b1, t1);
        out->addTriangle(b0, t1, t0);
        out->addTriangle(top, t0, t1);
        out->addTriangle(bottom, b1, b0);
      }
      break;
    }
    case ShapeType::kSphere: {
      const int n_lon = segmentsFor(s.radius, sagitta);
      const int n_lat = std::max(4, n_lon / 2);
      const uint32_t first = static_cast<uint32_t>(out->vertices.size() / 3);
      for (int j = 0; j <= n_lat; ++j) {
        const double theta = M_PI * j / n_lat;
        for (int i = 0; i < n_lon; ++i) {
          const double phi = 2 * M_PI * i / n_lon;
          out->addVertex(X * (s.radius * Eigen::Vector3d(std::sin(theta) * std::cos(phi),
                                                          std::sin(theta) * std::sin(phi),
                                                          std::cos(theta))));
        }
      }
      for (int j = 0; j < n_lat; ++j) {
        for (int i = 0; i < n_lon; ++i) {
          const uint32_t a = first + j * n_lon + i;
          const uint32_t b = first + j * n_lon + (i + 1) % n_lon;
          const uint32_t c = a + n_lon, d = b + n_lon;
          if (j > 0) out->addTriangle(a, b, d);
          if (j < n_lat - 1) out->addTriangle(a, d, c);
        }
      }
      break;
    }
    case ShapeType::kMesh: {
      const auto mesh = meshOf(s);
      const uint32_t base = static_cast<uint32_t>(out->vertices.size() / 3);
      for (const Eigen::Vector3f& v : mesh->vertices) out->addVertex(X * v.cast<double>());
      for (std::size_t i = 0; i + 2 < mesh->indices.size(); i += 3)
        out->addTriangle(base + mesh->indices[i], base + mesh->indices[i + 1],
                         base + mesh->indices[i + 2]);
      break;
    }
  }
}

void toEmbreeTransform(const Eigen::Isometry3d& X, float out[12]) {
  for (int c = 0; c < 3; ++c)
    for (int r = 0; r < 3; ++r) out[4 * 0 + c * 3 + r] = static_cast<float>(X.linear()(r, c));
  for (int r = 0; r < 3; ++r) out[9 + r] = static_cast<float>(X.translation()[r]);
}

// A body pose that may reach Embree: finite, its origin within kMaxBodyPosition.
bool poseInReach(const Eigen::Isometry3d& X) {
  return X.matrix().allFinite() &&
         X.translation().cwiseAbs().maxCoeff() <= RayCaster::kMaxBodyPosition;
}

// Bitwise equality of two poses (a NaN pose equals itself: no rebuild or commit per scan).
bool sameBits(const Eigen::Matrix4d& a, const Eigen::Matrix4d& b) {
  return std::memcmp(a.data(), b.data(), sizeof(double) * 16) == 0;
}

}  // namespace

struct RayCaster::Impl {
  /// The geometry of the static bodies (body < 0) or of one moving body.
  struct SubScene {
    int body = -1;
    RTCScene scene = nullptr;
    RTCGeometry instance = nullptr;
    std::vector<Analytic> prims;  // never resized after the user geometry is created
    Eigen::Matrix4d X_WB_last = Eigen::Matrix4d::Zero();
    bool left_out = false;  // disabled: the body's pose is out of reach (poseInReach)
    // What Embree holds, for exactDistance(): the triangles' vertices (sub-scene frame) and
    // indices, the geometry ids in the sub-scene, and the instance transform as the floats
    // Embree was given (and its inverse).
    std::vector<float> vertices;
    std::vector<uint32_t> indices;
    unsigned triangle_geom = RTC_INVALID_GEOMETRY_ID, user_geom = RTC_INVALID_GEOMETRY_ID;
    Eigen::Matrix4d M = Eigen::Matrix4d::Identity(), M_inv = Eigen::Matrix4d::Identity();
    void setTransform(const float xfm[12]) {
      M.setIdentity();
      for (int col = 0; col < 4; ++col)
        for (int r = 0; r < 3; ++r) M(r, col) = static_cast<double>(xfm[col * 3 + r]);
      M_inv = M.inverse();
    }
  };
  std::vector<int> sub_of_instance;  // top-scene geometry id -> index in subs

  RTCDevice device = nullptr;
  RTCScene top = nullptr;
  std::vector<std::unique_ptr<SubScene>> subs;
  std::vector<std::pair<int, Eigen::Matrix4d>> static_poses;  // rebuild when one changes
  bool built = false;
  std::size_t n_bodies = 0, n_items = 0;
  /// What each collision item was built from (body, placement, shape): a shape that changes
  /// size or kind, or items swapped for others of the same count (a model deleted and another
  /// spawned between two scans), rebuild too.
  struct ItemKey {
    int body = 0;
    Eigen::Matrix4d X_BS = Eigen::Matrix4d::Identity();
    Shape shape;
    // Bitwise, so that a NaN that was built once does not rebuild at every scan.
    template <typename T>
    static bool same(const T& a, const T& b) {
      return std::memcmp(&a, &b, sizeof(T)) == 0;
    }
    bool operator==(const SceneItem& item) const {
      const Shape& o = item.shape;
      const Eigen::Matrix4d X = item.X_BS.matrix();
      return body == item.body && same(X_BS, X) && shape.type == o.type &&
             same(shape.size, o.size) && same(shape.radius, o.radius) &&
             same(shape.length, o.length) && same(shape.normal, o.normal) &&
             same(shape.scale, o.scale) && shape.center_submesh == o.center_submesh &&
             shape.mesh_path == o.mesh_path && shape.submesh == o.submesh;
    }
  };
  std::vector<int> collision_items;  // indices into scene.items at the build
  std::vector<ItemKey> item_keys;     // ... and what they were
  bool itemsChanged(const Scene& scene) const {
    std::size_t k = 0;
    for (std::size_t i = 0; i < scene.items.size(); ++i) {
      if (!scene.items[i].collision) continue;
      if (k >= collision_items.size() || collision_items[k] != static_cast<int>(i) ||
          !(item_keys[k] == scene.items[i]))
        return true;
      ++k;
    }
    return k != collision_items.size();
  }
  std::size_t n_triangles = 0, n_analytic = 0, n_moving = 0, n_static_left_out = 0;
  std::string last_error;

  // Scan buffers, reused.
  std::vector<RTCRayHit> stream;

  /// The distance of a hit that Embree found (instance, geometry and primitive), computed again
  /// in double by one scalar routine from the ray as Embree was given it and the geometry it
  /// holds: Embree picks its kernels by the CPU's ISA at run time (SSE, AVX2, AVX-512), and their
  /// hit distances differ in the last bits; this one does not (issue 43). Embree's own distance
  /// is kept for a hit this routine cannot place (a ray parallel to the triangle's plane, a
  /// grazing analytic hit it misses).
  float exactDistance(const Eigen::Vector3f& o_f, const Eigen::Vector3f& d_f, unsigned instance,
                      unsigned geom, unsigned prim, float t_min, float t_max,
                      float embree_t) const {
    if (instance >= sub_of_instance.size() || sub_of_instance[instance] < 0) return embree_t;
    const SubScene& sub = *subs[sub_of_instance[instance]];
    const Eigen::Vector3d o = o_f.cast<double>(), d = d_f.cast<double>();
    if (geom == sub.triangle_geom && 3 * prim + 2 < sub.indices.size()) {
      Eigen::Vector3d w[3];
      for (int k = 0; k < 3; ++k) {
        const float* v = &sub.vertices[3 * sub.indices[3 * prim + k]];
        const Eigen::Vector4d v_S(v[0], v[1], v[2], 1.0);
        w[k] = (sub.M * v_S).head<3>();
      }
      const Eigen::Vector3d n = (w[1] - w[0]).cross(w[2] - w[0]);
      const double den = n.dot(d);
      if (den == 0.0) return embree_t;
      // Within the ray's segment, where Embree found the hit (rounding must not move a hit
      // at range min below it).
      return std::clamp(static_cast<float>(n.dot(w[0] - o) / den), t_min, t_max);
    }
    if (geom == sub.user_geom && prim < sub.prims.size()) {
      const Analytic& p = sub.prims[prim];
      const Eigen::Vector3d o_P = (sub.M_inv * Eigen::Vector4d(o.x(), o.y(), o.z(), 1.0)).head<3>();
      const Eigen::Vector3d d_P = sub.M_inv.topLeftCorner<3, 3>() * d;
      double t;
      Eigen::Vector3d n_S;
      if (intersectShape(p, p.X_SP * o_P, p.X_SP.linear() * d_P, t_min, t_max, &t, &n_S))
        return std::clamp(static_cast<float>(t), t_min, t_max);
    }
    return embree_t;
  }

  explicit Impl(const std::string& config) {
    device = rtcNewDevice(config.empty() ? nullptr : config.c_str());
    if (!device) throw RayCasterError("Embree: rtcNewDevice failed (config '" + config + "')");
    rtcSetDeviceErrorFunction(
        device,
        [](void* user, RTCError, const char* str) {
          static_cast<Impl*>(user)->last_error = str ? str : "unknown error";
        },
        this);
  }
  ~Impl() {
    clear();
    rtcReleaseDevice(device);
  }
  void clear() {
    for (auto& s : subs) {
      if (s->scene) rtcReleaseScene(s->scene);
    }
    subs.clear();
    static_poses.clear();
    sub_of_instance.clear();
    if (top) rtcReleaseScene(top);
    top = nullptr;
    built = false;
  }
  void check(const char* what) {
    const RTCError err = rtcGetDeviceError(device);
    if (err != RTC_ERROR_NONE)
      throw RayCasterError(std::string("Embree error while ") + what + ": " + last_error);
  }
};

RayCaster::RayCaster(RayCasterOptions options)
    : options_(options), impl_(std::make_unique<Impl>(options.embree_config)) {}

RayCaster::~RayCaster() = default;

void RayCaster::build(const Scene& scene) {
  Impl& m = *impl_;
  m.clear();
  m.n_triangles = m.n_analytic = m.n_moving = m.n_static_left_out = 0;
  // Which shapes go to user geometry (see PrimitiveMode).
  auto isAnalytic = [&](const Shape& shape, const Eigen::Isometry3d& X_PS) {
    switch (options_.primitives) {
      case PrimitiveMode::kAnalytic:
        return shape.type != ShapeType::kMesh;
      case PrimitiveMode::kTessellated:
        return false;
      case PrimitiveMode::kHybrid:
        break;
    }
    if (shape.type == ShapeType::kCylinder || shape.type == ShapeType::kSphere) return true;
    if (shape.type != ShapeType::kPlane) return false;
    // A plane is exact as triangles only if its normal is an axis of P: then the big
    // triangle's vertices have one coordinate exactly equal, whatever float rounding does.
    const Eigen::Vector3d n = X_PS.linear() * shape.normal.normalized();
    const Eigen::Vector3d a = n.cwiseAbs();
    return !((a.array() == 1.0).any() && (a.array() == 0.0).count() == 2);
  };

  // Group the collision items: sub-scene 0 = every static body (world frame).
  std::vector<int> sub_of_body(scene.bodies.size(), -1);
  std::vector<TriangleSoup> soups;
  auto subFor = [&](int body) -> int {
    const bool is_static = scene.bodies[body].is_static;
    const int key = is_static ? -1 : body;
    for (std::size_t i = 0; i < m.subs.size(); ++i)
      if (m.subs[i]->body == key) return static_cast<int>(i);
    m.subs.push_back(std::make_unique<Impl::SubScene>());
    m.subs.back()->body = key;
    soups.emplace_back();
    return static_cast<int>(m.subs.size() - 1);
  };
  for (std::size_t b = 0; b < scene.bodies.size(); ++b) {
    if (!scene.bodies[b].is_static) continue;
    m.static_poses.emplace_back(static_cast<int>(b), scene.bodies[b].X_WB.matrix());
    if (!poseInReach(scene.bodies[b].X_WB)) ++m.n_static_left_out;
  }

  for (const SceneItem& item : scene.items) {
    if (!item.collision) continue;
    if (item.body < 0 || item.body >= static_cast<int>(scene.bodies.size()))
      throw RayCasterError("scene item refers to body " + std::to_string(item.body) + " of " +
                           std::to_string(scene.bodies.size()));
    const SceneBody& body = scene.bodies[item.body];
    if (body.is_static && !poseInReach(body.X_WB)) continue;  // counted below
    const int s = subFor(item.body);
    const Eigen::Isometry3d X_PS = body.is_static ? body.X_WB * item.X_BS : item.X_BS;
    const ShapeType type = item.shape.type;
    if (isAnalytic(item.shape, X_PS)) {
      Analytic p;
      p.type = type;
      p.X_PS = X_PS;
      p.X_SP = X_PS.inverse();
      p.half = item.shape.size / 2;
      p.radius = item.shape.radius;
      p.half_length = item.shape.length / 2;
      p.normal = item.shape.normal.normalized();
      m.subs[s]->prims.push_back(p);
    } else {
      try {
        tessellate(item.shape, X_PS, options_.max_sagitta, &soups[s]);
      } catch (const MeshError& e) {
        throw RayCasterError("body '" + body.name + "': " + e.what());
      }
    }
  }

  m.top = rtcNewScene(m.device);
  rtcSetSceneFlags(m.top, RTC_SCENE_FLAG_DYNAMIC);
  rtcSetSceneBuildQuality(m.top, RTC_BUILD_QUALITY_LOW);
  for (std::size_t i = 0; i < m.subs.size(); ++i) {
    Impl::SubScene& sub = *m.subs[i];
    const TriangleSoup& soup = soups[i];
    sub.scene = rtcNewScene(m.device);
    rtcSetSceneBuildQuality(sub.scene, RTC_BUILD_QUALITY_HIGH);
    if (soup.triangleCount() > 0) {
      RTCGeometry g = rtcNewGeometry(m.device, RTC_GEOMETRY_TYPE_TRIANGLE);
      auto* v = static_cast<float*>(rtcSetNewGeometryBuffer(
          g, RTC_BUFFER_TYPE_VERTEX, 0, RTC_FORMAT_FLOAT3, 3 * sizeof(float),
          soup.vertices.size() / 3));
      auto* idx = static_cast<uint32_t*>(rtcSetNewGeometryBuffer(
          g, RTC_BUFFER_TYPE_INDEX, 0, RTC_FORMAT_UINT3, 3 * sizeof(uint32_t),
          soup.triangleCount()));
      if (!v || !idx) {
        rtcReleaseGeometry(g);
        m.check("allocating triangles");
        throw RayCasterError("Embree: cannot allocate triangle buffers");
      }
      std::copy(soup.vertices.begin(), soup.vertices.end(), v);
      std::copy(soup.indices.begin(), soup.indices.end(), idx);
      rtcCommitGeometry(g);
      sub.triangle_geom = rtcAttachGeometry(sub.scene, g);
      rtcReleaseGeometry(g);
      sub.vertices = soup.vertices;
      sub.indices = soup.indices;
      m.n_triangles += soup.triangleCount();
    }
    if (!sub.prims.empty()) {
      RTCGeometry g = rtcNewGeometry(m.device, RTC_GEOMETRY_TYPE_USER);
      rtcSetGeometryUserPrimitiveCount(g, static_cast<unsigned>(sub.prims.size()));
      rtcSetGeometryUserData(g, &sub.prims);
      rtcSetGeometryBoundsFunction(g, analyticBounds, nullptr);
      rtcSetGeometryIntersectFunction(g, analyticIntersect);
      rtcSetGeometryOccludedFunction(g, analyticOccluded);
      rtcCommitGeometry(g);
      sub.user_geom = rtcAttachGeometry(sub.scene, g);
      rtcReleaseGeometry(g);
      m.n_analytic += sub.prims.size();
    }
    rtcCommitScene(sub.scene);

    sub.instance = rtcNewGeometry(m.device, RTC_GEOMETRY_TYPE_INSTANCE);
    rtcSetGeometryInstancedScene(sub.instance, sub.scene);
    rtcSetGeometryTimeStepCount(sub.instance, 1);
    const Eigen::Isometry3d X = sub.body < 0 ? Eigen::Isometry3d::Identity()
                                             : scene.bodies[sub.body].X_WB;
    sub.left_out = !poseInReach(X);
    float xfm[12];
    toEmbreeTransform(sub.left_out ? Eigen::Isometry3d::Identity() : X, xfm);
    rtcSetGeometryTransform(sub.instance, 0, RTC_FORMAT_FLOAT3X4_COLUMN_MAJOR, xfm);
    sub.setTransform(xfm);
    sub.X_WB_last = X.matrix();
    if (sub.left_out) rtcDisableGeometry(sub.instance);
    rtcCommitGeometry(sub.instance);
    const unsigned instance_id = rtcAttachGeometry(m.top, sub.instance);
    if (m.sub_of_instance.size() <= instance_id) m.sub_of_instance.resize(instance_id + 1, -1);
    m.sub_of_instance[instance_id] = static_cast<int>(i);
    rtcReleaseGeometry(sub.instance);  // the top scene holds it
    if (sub.body >= 0) ++m.n_moving;
  }
  rtcCommitScene(m.top);
  m.check("building the ray-casting scene");
  m.n_bodies = scene.bodies.size();
  m.n_items = scene.items.size();
  m.collision_items.clear();
  m.item_keys.clear();
  for (std::size_t i = 0; i < scene.items.size(); ++i) {
    const SceneItem& item = scene.items[i];
    if (!item.collision) continue;
    m.collision_items.push_back(static_cast<int>(i));
    m.item_keys.push_back({item.body, item.X_BS.matrix(), item.shape});
  }
  m.built = true;
}

void RayCaster::setProfile(StepProfile* profile) {
  profile_ = profile;
  update_row_ = profileRow(profile, "sensors: sample / ray-casting scene: moved bodies committed");
  cast_row_ = profileRow(profile, "sensors: sample / ray-casting: rays cast");
}

void RayCaster::update(const Scene& scene) {
  StepProfile::Scope timed(profile_, update_row_);
  Impl& m = *impl_;
  bool rebuild = !m.built || m.n_bodies != scene.bodies.size() || m.n_items != scene.items.size() ||
                 m.itemsChanged(scene);
  for (std::size_t i = 0; !rebuild && i < m.static_poses.size(); ++i) {
    const auto& sp = m.static_poses[i];
    rebuild = !scene.bodies[sp.first].is_static || !sameBits(scene.bodies[sp.first].X_WB.matrix(), sp.second);
  }
  if (rebuild) build(scene);
  bool changed = false;
  for (auto& sub : m.subs) {
    if (sub->body < 0) continue;
    const Eigen::Isometry3d& X = scene.bodies[sub->body].X_WB;
    if (sameBits(X.matrix(), sub->X_WB_last)) continue;
    sub->X_WB_last = X.matrix();
    if (!poseInReach(X)) {  // left out, its last transform kept (it never reaches Embree)
      if (!sub->left_out) {
        rtcDisableGeometry(sub->instance);
        rtcCommitGeometry(sub->instance);
        sub->left_out = true;
        changed = true;
      }
      continue;
    }
    float xfm[12];
    toEmbreeTransform(X, xfm);
    rtcSetGeometryTransform(sub->instance, 0, RTC_FORMAT_FLOAT3X4_COLUMN_MAJOR, xfm);
    sub->setTransform(xfm);
    if (sub->left_out) rtcEnableGeometry(sub->instance);
    sub->left_out = false;
    rtcCommitGeometry(sub->instance);
    changed = true;
  }
  if (changed) {
    rtcCommitScene(m.top);
    m.check("moving bodies");
  }
}

void RayCaster::castRays(const Eigen::Vector3d& origin_W,
                         const std::vector<Eigen::Vector3f>& directions, float t_min,
                         float t_max, float* distances) {
  StepProfile::Scope timed(profile_, cast_row_);
  Impl& m = *impl_;
  assert(t_min >= 0.0f && t_min <= t_max);
  const int n = static_cast<int>(directions.size());
  const float inf = std::numeric_limits<float>::infinity();
  // Embree aborts (an assertion in Debian's build) on a ray origin that is not finite or beyond
  // about 1.8e18; a sensor that far out sees nothing (found with set_model_state at 1e30).
  constexpr double kMaxOrigin = 1e15;
  if (!m.built || m.subs.empty() || !origin_W.allFinite() ||
      origin_W.cwiseAbs().maxCoeff() > kMaxOrigin) {
    std::fill(distances, distances + n, inf);
    return;
  }
  const Eigen::Vector3f o = origin_W.cast<float>();
  RTCIntersectContext context;
  rtcInitIntersectContext(&context);
  switch (options_.query) {
    case RayQueryMode::kSingle: {
      for (int i = 0; i < n; ++i) {
        RTCRayHit rh;
        setUpRay(&rh, o, directions[i], t_min, t_max, i);
        rtcIntersect1(m.top, &context, &rh);
        distances[i] = rh.hit.geomID == RTC_INVALID_GEOMETRY_ID
                           ? inf
                           : m.exactDistance(o, Eigen::Vector3f(rh.ray.dir_x, rh.ray.dir_y, rh.ray.dir_z),
                                             rh.hit.instID[0], rh.hit.geomID, rh.hit.primID,
                                             t_min, t_max, rh.ray.tfar);
      }
      break;
    }
    case RayQueryMode::kPacket16: {
      context.flags = RTC_INTERSECT_CONTEXT_FLAG_COHERENT;
      RTCRayHit16 rh;
      alignas(64) int valid[16];
      for (int start = 0; start < n; start += 16) {
        const int count = std::min(16, n - start);
        for (int j = 0; j < 16; ++j) {
          const int i = start + std::min(j, count - 1);
          valid[j] = j < count ? -1 : 0;
          rh.ray.org_x[j] = o.x(), rh.ray.org_y[j] = o.y(), rh.ray.org_z[j] = o.z();
          rh.ray.dir_x[j] = embreeComponent(directions[i].x());
          rh.ray.dir_y[j] = embreeComponent(directions[i].y());
          rh.ray.dir_z[j] = embreeComponent(directions[i].z());
          rh.ray.tnear[j] = t_min;
          rh.ray.tfar[j] = t_max;
          rh.ray.time[j] = 0.0f;
          rh.ray.mask[j] = 0xFFFFFFFFu;
          rh.ray.id[j] = i;
          rh.ray.flags[j] = 0;
          rh.hit.geomID[j] = RTC_INVALID_GEOMETRY_ID;
          rh.hit.instID[0][j] = RTC_INVALID_GEOMETRY_ID;
        }
        rtcIntersect16(valid, m.top, &context, &rh);
        for (int j = 0; j < count; ++j) {
          distances[start + j] =
              rh.hit.geomID[j] == RTC_INVALID_GEOMETRY_ID
                  ? inf
                  : m.exactDistance(o, Eigen::Vector3f(rh.ray.dir_x[j], rh.ray.dir_y[j], rh.ray.dir_z[j]),
                                    rh.hit.instID[0][j], rh.hit.geomID[j], rh.hit.primID[j], t_min,
                                    t_max, rh.ray.tfar[j]);
        }
      }
      break;
    }
    case RayQueryMode::kStream: {
      context.flags = RTC_INTERSECT_CONTEXT_FLAG_COHERENT;
      m.stream.resize(n);
      for (int i = 0; i < n; ++i) setUpRay(&m.stream[i], o, directions[i], t_min, t_max, i);
      rtcIntersect1M(m.top, &context, m.stream.data(), n, sizeof(RTCRayHit));
      for (int i = 0; i < n; ++i) {
        const RTCRayHit& h = m.stream[i];
        distances[i] = h.hit.geomID == RTC_INVALID_GEOMETRY_ID
                           ? inf
                           : m.exactDistance(o, Eigen::Vector3f(h.ray.dir_x, h.ray.dir_y, h.ray.dir_z),
                                             h.hit.instID[0], h.hit.geomID, h.hit.primID, t_min,
                                             t_max, h.ray.tfar);
      }
      break;
    }
  }
}

std::size_t RayCaster::triangleCount() const { return impl_->n_triangles; }
std::size_t RayCaster::analyticCount() const { return impl_->n_analytic; }
std::size_t RayCaster::movingBodyCount() const { return impl_->n_moving; }

std::size_t RayCaster::leftOutBodyCount() const {
  std::size_t n = impl_->n_static_left_out;
  for (const auto& sub : impl_->subs) n += sub->body >= 0 && sub->left_out;
  return n;
}

}  // namespace tianracer_sim
