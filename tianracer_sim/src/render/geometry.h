// Triangle soups for the renderer: unit primitives and meshes with crease-angle normals.
#ifndef TIANRACER_SIM_SRC_RENDER_GEOMETRY_H
#define TIANRACER_SIM_SRC_RENDER_GEOMETRY_H

#include <vector>

#include "tianracer_sim/mesh/mesh_loader.h"

namespace tianracer_sim {
namespace render_internal {

/// Interleaved position (3 floats) + normal (3 floats) + texture coordinates (2 floats, v up
/// from the bottom of the image), three vertices per triangle, counter-clockwise seen from the
/// side the normal points to.
struct Vertex {
  float p[3];
  float n[3];
  float t[2];
};
using Soup = std::vector<Vertex>;

/// Cube of side 1 centred at the origin (scaled per item to the box size); each face maps the
/// whole texture (as Ogre's box).
Soup unitBox();
/// Cylinder of radius 1 and length 1 along z, centred, `segments` around; u around, v along z.
Soup unitCylinder(int segments = 32);
/// Sphere of radius 1, `slices` around z and `stacks` from pole to pole; u around, v up.
Soup unitSphere(int slices = 32, int stacks = 16);
/// Square of side 1 in the z = 0 plane, facing +z; u = x + 1/2, v = y + 1/2 (seen from +z with
/// x to the right, the image is upright).
Soup unitQuad();

/// A run of triangles of one mesh material (-1: the file gave none), in soup vertices.
struct MeshPart {
  std::size_t first = 0;
  std::size_t count = 0;
  int material = -1;
};

/// Expands an indexed mesh into a soup. Each corner's normal averages the (area-weighted)
/// normals of the triangles around its vertex that lie within `crease_deg` of its own
/// triangle: smooth cylinders, sharp box edges. Degenerate triangles are dropped. With
/// `parts`, the triangles are grouped by mesh material (their order kept within a group) and
/// the groups listed; corners carry the mesh's corner_uvs when it has them.
Soup meshSoup(const TriangleMesh& mesh, double crease_deg = 40.0,
              std::vector<MeshPart>* parts = nullptr);

}  // namespace render_internal
}  // namespace tianracer_sim

#endif  // TIANRACER_SIM_SRC_RENDER_GEOMETRY_H
