#include "geometry.h"

#include <algorithm>
#include <cmath>

#include <Eigen/Geometry>

namespace tianracer_sim {
namespace render_internal {
namespace {

void push(Soup* s, const Eigen::Vector3f& p, const Eigen::Vector3f& n,
          const Eigen::Vector2f& t = Eigen::Vector2f::Zero()) {
  s->push_back(Vertex{{p.x(), p.y(), p.z()}, {n.x(), n.y(), n.z()}, {t.x(), t.y()}});
}

void tri(Soup* s, const Eigen::Vector3f& a, const Eigen::Vector3f& b, const Eigen::Vector3f& c,
         const Eigen::Vector3f& n, const Eigen::Vector2f& ta = Eigen::Vector2f::Zero(),
         const Eigen::Vector2f& tb = Eigen::Vector2f::Zero(),
         const Eigen::Vector2f& tc = Eigen::Vector2f::Zero()) {
  push(s, a, n, ta);
  push(s, b, n, tb);
  push(s, c, n, tc);
}

// Planar texture coordinates of a point of a unit cap: (x, y) in [-1, 1] -> [0, 1].
Eigen::Vector2f capUv(const Eigen::Vector3f& p) { return {0.5f * p.x() + 0.5f, 0.5f * p.y() + 0.5f}; }

}  // namespace

Soup unitBox() {
  Soup s;
  // For each axis and sign: a face with outward normal n and two in-plane axes u, v with
  // u x v = n so that (0,0) (1,0) (1,1) is counter-clockwise seen from outside.
  for (int axis = 0; axis < 3; ++axis) {
    for (int sign = -1; sign <= 1; sign += 2) {
      Eigen::Vector3f n = Eigen::Vector3f::Zero();
      n[axis] = static_cast<float>(sign);
      Eigen::Vector3f u = Eigen::Vector3f::Zero();
      u[(axis + 1) % 3] = 1.0f;
      Eigen::Vector3f v = n.cross(u);
      const Eigen::Vector3f c = 0.5f * n;
      const Eigen::Vector3f p00 = c - 0.5f * u - 0.5f * v, p10 = c + 0.5f * u - 0.5f * v;
      const Eigen::Vector3f p11 = c + 0.5f * u + 0.5f * v, p01 = c - 0.5f * u + 0.5f * v;
      const Eigen::Vector2f t00(0, 0), t10(1, 0), t11(1, 1), t01(0, 1);
      tri(&s, p00, p10, p11, n, t00, t10, t11);
      tri(&s, p00, p11, p01, n, t00, t11, t01);
    }
  }
  return s;
}

Soup unitCylinder(int segments) {
  Soup s;
  const float h = 0.5f;
  for (int i = 0; i < segments; ++i) {
    const double a0 = 2.0 * M_PI * i / segments, a1 = 2.0 * M_PI * (i + 1) / segments;
    const Eigen::Vector3f r0(std::cos(a0), std::sin(a0), 0.0f), r1(std::cos(a1), std::sin(a1), 0.0f);
    const Eigen::Vector3f up(0, 0, h);
    const float u0 = static_cast<float>(i) / segments, u1 = static_cast<float>(i + 1) / segments;
    // Side: smooth normals.
    push(&s, r0 - up, r0, {u0, 0});
    push(&s, r1 - up, r1, {u1, 0});
    push(&s, r1 + up, r1, {u1, 1});
    push(&s, r0 - up, r0, {u0, 0});
    push(&s, r1 + up, r1, {u1, 1});
    push(&s, r0 + up, r0, {u0, 1});
    // Caps.
    tri(&s, up, r0 + up, r1 + up, Eigen::Vector3f::UnitZ(), capUv(up), capUv(r0), capUv(r1));
    tri(&s, -up, r1 - up, r0 - up, -Eigen::Vector3f::UnitZ(), capUv(-up), capUv(r1), capUv(r0));
  }
  return s;
}

Soup unitSphere(int slices, int stacks) {
  Soup s;
  auto at = [&](int i, int j) {
    const double theta = M_PI * j / stacks;  // from +z
    const double phi = 2.0 * M_PI * i / slices;
    return Eigen::Vector3f(std::sin(theta) * std::cos(phi), std::sin(theta) * std::sin(phi),
                           std::cos(theta));
  };
  auto uv = [&](int i, int j) {
    return Eigen::Vector2f(static_cast<float>(i) / slices, 1.0f - static_cast<float>(j) / stacks);
  };
  for (int j = 0; j < stacks; ++j) {
    for (int i = 0; i < slices; ++i) {
      const Eigen::Vector3f a = at(i, j), b = at(i, j + 1), c = at(i + 1, j + 1), d = at(i + 1, j);
      if (j != 0) {  // the top stack's first triangle is degenerate
        push(&s, a, a, uv(i, j));
        push(&s, b, b, uv(i, j + 1));
        push(&s, d, d, uv(i + 1, j));
      }
      if (j != stacks - 1) {
        push(&s, b, b, uv(i, j + 1));
        push(&s, c, c, uv(i + 1, j + 1));
        push(&s, d, d, uv(i + 1, j));
      }
    }
  }
  return s;
}

Soup unitQuad() {
  Soup s;
  const Eigen::Vector3f n = Eigen::Vector3f::UnitZ();
  const Eigen::Vector3f p00(-.5f, -.5f, 0), p10(.5f, -.5f, 0), p11(.5f, .5f, 0), p01(-.5f, .5f, 0);
  const Eigen::Vector2f t00(0, 0), t10(1, 0), t11(1, 1), t01(0, 1);
  tri(&s, p00, p10, p11, n, t00, t10, t11);
  tri(&s, p00, p11, p01, n, t00, t11, t01);
  return s;
}

Soup meshSoup(const TriangleMesh& mesh, double crease_deg, std::vector<MeshPart>* parts) {
  const std::size_t nt = mesh.triangleCount();
  std::vector<Eigen::Vector3f> face_n(nt);      // area-weighted (|n| = 2 area)
  std::vector<Eigen::Vector3f> face_unit(nt);
  std::vector<bool> keep(nt, false);
  for (std::size_t t = 0; t < nt; ++t) {
    const Eigen::Vector3f& a = mesh.vertices[mesh.indices[3 * t]];
    const Eigen::Vector3f& b = mesh.vertices[mesh.indices[3 * t + 1]];
    const Eigen::Vector3f& c = mesh.vertices[mesh.indices[3 * t + 2]];
    face_n[t] = (b - a).cross(c - a);
    const float len = face_n[t].norm();
    keep[t] = len > 0.0f && std::isfinite(len);
    face_unit[t] = keep[t] ? Eigen::Vector3f(face_n[t] / len) : Eigen::Vector3f::Zero();
  }
  // Triangles around each vertex (CSR layout).
  std::vector<uint32_t> start(mesh.vertices.size() + 1, 0);
  for (std::size_t t = 0; t < nt; ++t) {
    if (!keep[t]) continue;
    for (int k = 0; k < 3; ++k) ++start[mesh.indices[3 * t + k] + 1];
  }
  for (std::size_t v = 0; v < mesh.vertices.size(); ++v) start[v + 1] += start[v];
  std::vector<uint32_t> around(start.back());
  std::vector<uint32_t> fill(start.begin(), start.end() - 1);
  for (std::size_t t = 0; t < nt; ++t) {
    if (!keep[t]) continue;
    for (int k = 0; k < 3; ++k) around[fill[mesh.indices[3 * t + k]]++] = static_cast<uint32_t>(t);
  }
  const float cos_crease = static_cast<float>(std::cos(crease_deg * M_PI / 180.0));
  // Triangle order: as in the file, or grouped by material (stable) for `parts`.
  std::vector<std::size_t> order;
  order.reserve(nt);
  for (std::size_t t = 0; t < nt; ++t) {
    if (keep[t]) order.push_back(t);
  }
  const bool by_material = parts != nullptr && mesh.triangle_material.size() == nt;
  auto material = [&](std::size_t t) { return by_material ? mesh.triangle_material[t] : -1; };
  if (by_material) {
    std::stable_sort(order.begin(), order.end(),
                     [&](std::size_t a, std::size_t b) { return material(a) < material(b); });
  }
  const bool uvs = mesh.corner_uvs.size() == mesh.indices.size();
  Soup s;
  s.reserve(3 * order.size());
  if (parts) parts->clear();
  for (std::size_t t : order) {
    if (parts && (parts->empty() || parts->back().material != material(t))) {
      parts->push_back(MeshPart{s.size(), 0, material(t)});
    }
    for (int k = 0; k < 3; ++k) {
      const uint32_t v = mesh.indices[3 * t + k];
      Eigen::Vector3f n = Eigen::Vector3f::Zero();
      for (uint32_t i = start[v]; i < start[v + 1]; ++i) {
        const uint32_t g = around[i];
        if (face_unit[g].dot(face_unit[t]) >= cos_crease) n += face_n[g];
      }
      const float len = n.norm();
      n = len > 0.0f ? Eigen::Vector3f(n / len) : face_unit[t];
      push(&s, mesh.vertices[v], n, uvs ? mesh.corner_uvs[3 * t + k] : Eigen::Vector2f::Zero());
    }
    if (parts) parts->back().count += 3;
  }
  return s;
}

}  // namespace render_internal
}  // namespace tianracer_sim
