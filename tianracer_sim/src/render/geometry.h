// Triangle soups for the renderer: unit primitives and meshes with crease-angle normals.
#ifndef TIANRACER_SIM_SRC_RENDER_GEOMETRY_H
#define TIANRACER_SIM_SRC_RENDER_GEOMETRY_H

#include <vector>

#include "tianracer_sim/mesh/mesh_loader.h"

namespace tianracer_sim {
namespace render_internal {

/// Interleaved position (3 floats) + normal (3 floats), three vertices per triangle,
/// counter-clockwise seen from the side the normal points to.
struct Vertex {
  float p[3];
  float n[3];
};
using Soup = std::vector<Vertex>;

/// Cube of side 1 centred at the origin (scaled per item to the box size).
Soup unitBox();
/// Cylinder of radius 1 and length 1 along z, centred, `segments` around.
Soup unitCylinder(int segments = 32);
/// Sphere of radius 1, `slices` around z and `stacks` from pole to pole.
Soup unitSphere(int slices = 32, int stacks = 16);
/// Square of side 1 in the z = 0 plane, facing +z.
Soup unitQuad();

/// Expands an indexed mesh into a soup. Each corner's normal averages the (area-weighted)
/// normals of the triangles around its vertex that lie within `crease_deg` of its own
/// triangle: smooth cylinders, sharp box edges. Degenerate triangles are dropped.
Soup meshSoup(const TriangleMesh& mesh, double crease_deg = 40.0);

}  // namespace render_internal
}  // namespace tianracer_sim

#endif  // TIANRACER_SIM_SRC_RENDER_GEOMETRY_H
