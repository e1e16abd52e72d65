// libFuzzer harness: the URDF extension parser (<gazebo>, <transmission>, plugins, sensors) and
// the whole loadRobotModel on the same bytes. Both may only return or throw ModelError; any other
// exception, a sanitizer report or a result that breaks the loader's promises is a crash.
//   scripts/fuzz.sh [seconds]
#include <cmath>
#include <cstdint>
#include <string>

#include <urdf_model/model.h>

#include "fuzz_check.h"
#include "tianracer_sim/model/robot_model.h"

namespace {

const tianracer_sim_fuzz::PromiseCheck check{"fuzz_extensions"};

// What loadRobotModel validates on success (validated once, on load).
void checkModel(const tianracer_sim::RobotModel& m) {
  check(m.urdf != nullptr, "urdf is null");
  for (const auto& [name, link] : m.urdf->links_) {
    if (!link || !link->inertial) continue;
    const urdf::Inertial& i = *link->inertial;
    check(std::isfinite(i.mass) && i.mass > 0.0, "accepted a non-positive or non-finite mass");
    check(std::isfinite(i.ixx) && std::isfinite(i.iyy) && std::isfinite(i.izz) &&
              std::isfinite(i.ixy) && std::isfinite(i.ixz) && std::isfinite(i.iyz),
          "accepted a non-finite inertia");
  }
  for (const auto& t : m.ext.transmissions) {
    check(std::isfinite(t.mechanical_reduction) && t.mechanical_reduction != 0.0,
          "accepted a zero or non-finite mechanicalReduction");
    check(m.urdf->getJoint(t.joint) != nullptr, "transmission on an unknown joint accepted");
  }
  for (const auto& [name, ext] : m.ext.links)
    for (const auto& s : ext.sensors) {
      check(s.X_LS.matrix().allFinite(), "sensor pose not finite");
      check(std::isfinite(s.update_rate) && s.update_rate >= 0.0, "bad sensor update_rate");
    }
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  const std::string xml(reinterpret_cast<const char*>(data), size);
  try {
    tianracer_sim::parseExtensions(xml, "fuzz.urdf", nullptr);
  } catch (const tianracer_sim::ModelError&) {
  }
  tianracer_sim::LoadOptions options;
  options.resolver.find_package = [](const std::string&) { return std::string(); };
  options.resolver.base_dir = "/nonexistent";
  options.require_meshes = false;  // meshes are files: not what is fuzzed here
  options.warn = [](const std::string&) {};
  try {
    checkModel(tianracer_sim::loadRobotModel(xml, "fuzz.urdf", options));
  } catch (const tianracer_sim::ModelError&) {
  }
  return 0;
}
