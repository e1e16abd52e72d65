// The promises of the mesh loader, checked on one file: the fuzz harness (fuzz_mesh.cpp) and
// the replay of the regression corpus (test/unit/test_mesh_fuzz_regressions.cpp) run the same
// checks, so that CI, which has no libFuzzer, replays what the fuzzer found. Header-only.
//
// A file either loads into a usable mesh (triangles, indices in range, finite vertices within
// the coordinate limit, per-corner UVs and per-triangle materials that match) or is refused
// with MeshError. Anything else breaks a promise: another exception, a crash or sanitizer
// report (the harness), or an assimp allocation failure reported as a clean error (std::bad_alloc,
// vector::reserve): the limits must refuse such a file before assimp allocates.
#ifndef TIANRACER_SIM_FUZZ_MESH_REPLAY_H
#define TIANRACER_SIM_FUZZ_MESH_REPLAY_H

#include <cmath>
#include <exception>
#include <string>

#include <tianracer_assets/mesh.h>

namespace tianracer_sim_fuzz {

/// What broke in `mesh` ("" when nothing). `materials`: loaded by loadMeshWithMaterials.
inline std::string brokenMeshPromise(const tianracer_assets::TriangleMesh& mesh, bool materials) {
  if (mesh.indices.empty() || mesh.indices.size() % 3 != 0) return "a mesh without whole triangles was accepted";
  for (uint32_t i : mesh.indices) {
    if (i >= mesh.vertices.size()) return "a triangle index is out of range";
  }
  for (const auto& v : mesh.vertices) {
    if (!v.allFinite()) return "a non-finite vertex was accepted";
    if (v.cwiseAbs().maxCoeff() > 1e6f) return "a vertex beyond 1e6 m was accepted";
  }
  if (materials) {
    if (!mesh.corner_uvs.empty() && mesh.corner_uvs.size() != mesh.indices.size())
      return "corner UVs do not match the corners";
    if (mesh.triangle_material.size() != mesh.triangleCount()) return "triangle materials do not match";
    for (int m : mesh.triangle_material) {
      if (m < -1 || m >= static_cast<int>(mesh.materials.size())) return "a material index is out of range";
    }
  }
  return "";
}

/// Loads `path` both ways (collision and rendering) and returns the broken promise, or "" when
/// each load either gave a usable mesh or a MeshError.
inline std::string replayMeshFile(const std::string& path) {
  for (bool materials : {false, true}) {
    try {
      const tianracer_assets::TriangleMesh mesh = materials ? tianracer_assets::loadMeshFileWithMaterials(path)
                                                            : tianracer_assets::loadMeshFile(path);
      const std::string broken = brokenMeshPromise(mesh, materials);
      if (!broken.empty()) return broken;
    } catch (const tianracer_assets::MeshError& e) {
      // assimp's reason comes right after "unreadable (" (a message of the checks may quote
      // the file's text, which may say anything: fuzz_harness_bad_alloc_quoted.dae).
      const std::string what = e.what();
      const std::string prefix = "mesh '" + path + "': unreadable (";
      if (what.rfind(prefix, 0) == 0) {
        const std::string why = what.substr(prefix.size());
        for (const char* oom : {"std::bad_alloc", "vector::", "cannot create std::vector", "std::length_error"}) {
          if (why.rfind(oom, 0) == 0) return "assimp ran out of memory instead of a limit refusing the file: " + what;
        }
      }
    } catch (const std::exception& e) {
      return std::string("an exception other than MeshError: ") + e.what();
    }
  }
  return "";
}

}  // namespace tianracer_sim_fuzz

#endif  // TIANRACER_SIM_FUZZ_MESH_REPLAY_H
