// libFuzzer harness: a mutated controller YAML through the one robot set-up (YamlControlParams,
// setUpRobot), its controllers built on a robot and stepped with commands taken from the input
// (controller_replay.h, which the regression test replays too). The first byte picks the robot
// ('t' the tianracer, 's' steerbot, anything else diffbot); the rest is the YAML. Set-up may
// only end in InputError; any other exception (a yaml-cpp one leaking out), a sanitizer report
// or state that stops being finite is a crash.
//   FUZZ_TARGETS=controllers scripts/fuzz.sh [seconds]
#include <unistd.h>

#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <string>

#include "controller_replay.h"
#include "fuzz_check.h"

namespace {

const tianracer_sim_fuzz::PromiseCheck check{"fuzz_controllers"};

const std::string& yamlPath() {
  static const std::string path = [] {
    char tmpl[] = "/tmp/fuzz_controllers_XXXXXX";
    const char* d = ::mkdtemp(tmpl);
    if (!d) std::abort();
    return std::string(d) + "/control.yaml";
  }();
  return path;
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  if (size == 0) return 0;
  const tianracer_sim::RobotModel& model =
      tianracer_sim_fuzz::controllerReplayRobot(static_cast<char>(data[0]));
  const std::string yaml(reinterpret_cast<const char*>(data) + 1, size - 1);
  const std::string& path = yamlPath();
  std::FILE* f = std::fopen(path.c_str(), "wb");
  if (!f) std::abort();
  std::fwrite(yaml.data(), 1, yaml.size(), f);
  std::fclose(f);
  try {
    const std::string broken = tianracer_sim_fuzz::replayControllerYaml(model, path, yaml);
    check(broken.empty(), broken.c_str());
  } catch (const tianracer_sim::InputError&) {
  }
  ::unlink(path.c_str());
  return 0;
}
