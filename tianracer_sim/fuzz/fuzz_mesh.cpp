// libFuzzer harness: mesh files through the loader the simulator uses (tianracer_assets'
// loadMeshFile and loadMeshFileWithMaterials: the COLLADA pre-pass, assimp, the scene check).
// The first byte of an input picks the file name assimp sees: 'd' fuzz.dae, 's' fuzz.stl,
// anything else fuzz.obj; the rest is the file. A crash, a sanitizer report, an exception other
// than MeshError, an out-of-memory error from assimp or an accepted mesh that breaks a promise
// (mesh_replay.h) is a finding.
//   scripts/fuzz.sh [seconds]
#include <unistd.h>

#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <string>

#include "fuzz_check.h"
#include "mesh_replay.h"

namespace {

const tianracer_sim_fuzz::PromiseCheck check{"fuzz_mesh"};

const std::string& workDir() {
  static const std::string dir = [] {
    char tmpl[] = "/tmp/fuzz_mesh_XXXXXX";
    const char* d = ::mkdtemp(tmpl);
    if (!d) std::abort();
    return std::string(d);
  }();
  return dir;
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  if (size == 0) return 0;
  const char* ext = data[0] == 'd' ? "dae" : data[0] == 's' ? "stl" : "obj";
  const std::string path = workDir() + "/fuzz." + ext;
  std::FILE* f = std::fopen(path.c_str(), "wb");
  if (!f) std::abort();
  if (size > 1) std::fwrite(data + 1, 1, size - 1, f);
  std::fclose(f);
  const std::string broken = tianracer_sim_fuzz::replayMeshFile(path);
  check(broken.empty(), broken.c_str());
  ::unlink(path.c_str());
  return 0;
}
