// libFuzzer harness: the SDF world subset loader (loadWorldString). It may only return or throw
// WorldError; any other exception, a sanitizer report or an accepted world with a non-finite
// pose or a non-positive size is a crash.
//   scripts/fuzz.sh [seconds]
#include <cmath>
#include <cstdint>
#include <string>

#include "fuzz_check.h"
#include "tianracer_sim/world/world.h"

namespace {

const tianracer_sim_fuzz::PromiseCheck check{"fuzz_world"};

void checkWorld(const tianracer_sim::WorldDescription& w) {
  check(std::isfinite(w.physics.max_step_size) && w.physics.max_step_size > 0.0,
        "accepted a bad max_step_size");
  check(w.physics.gravity.allFinite(), "accepted a non-finite gravity");
  check(w.X_WG.matrix().allFinite(), "ground plane pose not finite");
  for (const auto& m : w.models) {
    check(m.X_WM.matrix().allFinite(), "model pose not finite");
    for (const auto& l : m.links) {
      check(l.X_ML.matrix().allFinite(), "link pose not finite");
      if (!m.is_static)
        check(std::isfinite(l.inertial.mass) && l.inertial.mass > 0.0,
              "dynamic link with a non-positive mass accepted");
      for (const auto& c : l.collisions) check(c.X_LS.matrix().allFinite(), "collision pose");
      for (const auto& v : l.visuals) check(v.X_LS.matrix().allFinite(), "visual pose");
    }
  }
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  const std::string xml(reinterpret_cast<const char*>(data), size);
  tianracer_sim::WorldLoadOptions options;
  options.require_meshes = false;  // mesh files are not what is fuzzed here
  options.warn = [](const std::string&) {};
  try {
    checkWorld(tianracer_sim::loadWorldString(xml, "fuzz.world", "/nonexistent", options));
  } catch (const tianracer_sim::WorldError&) {
  }
  return 0;
}
