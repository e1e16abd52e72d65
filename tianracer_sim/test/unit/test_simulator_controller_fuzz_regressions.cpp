// The controller-YAML regression corpus of issue 43 (test/data/fuzz_regressions/controllers/):
// hand-made bad configurations and every input fuzz_controllers found, each replayed with the
// harness's own code (fuzz/controller_replay.h): set up through YamlControlParams and setUpRobot,
// built on its robot (named by the file's prefix: tianracer_, steerbot_, diffbot_) and stepped
// with commands. It must end in a clean InputError or stay finite; nothing else may happen.
#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include "../../fuzz/controller_replay.h"

namespace tianracer_sim {
namespace {

const std::string kCorpus = std::string(TEST_DATA_DIR) + "/fuzz_regressions/controllers/";

struct Outcome {
  std::string broken;  // a broken promise ("" none)
  std::string error;   // the clean error's text ("" none)
};

Outcome replay(const std::string& name) {
  const std::string file = kCorpus + name;
  std::ifstream in(file);
  std::stringstream text;
  text << in.rdbuf();
  const char pick = name.rfind("tianracer_", 0) == 0 ? 't' : name.rfind("steerbot_", 0) == 0 ? 's' : 'd';
  Outcome out;
  try {
    out.broken = tianracer_sim_fuzz::replayControllerYaml(
        tianracer_sim_fuzz::controllerReplayRobot(pick), file, text.str());
  } catch (const InputError& e) {
    out.error = e.what();
  }
  return out;
}

std::vector<std::string> corpus() {
  std::vector<std::string> names;
  for (const auto& e : std::filesystem::directory_iterator(kCorpus)) {
    const std::string n = e.path().filename().string();
    if (n != "README.md") names.push_back(n);
  }
  std::sort(names.begin(), names.end());
  return names;
}

TEST(ControllerFuzzRegressions, EveryFileStaysFiniteOrIsACleanError) {
  const std::vector<std::string> names = corpus();
  ASSERT_GE(names.size(), 12u) << "the corpus is missing in " << kCorpus;
  for (const std::string& n : names) {
    SCOPED_TRACE(n);
    const Outcome o = replay(n);
    EXPECT_EQ(o.broken, "");
    // A file named *_valid_* must load; the others may be refused, with the YAML's file and
    // line first.
    if (n.find("_valid_") != std::string::npos) EXPECT_EQ(o.error, "");
    if (!o.error.empty()) EXPECT_EQ(o.error.rfind(kCorpus + n + ":", 0), 0u) << o.error;
  }
}

TEST(ControllerFuzzRegressions, EachCaseGivesItsMessage) {
  const auto contains = [](const std::string& error, const std::string& text) {
    return error.find(text) != std::string::npos;
  };
  EXPECT_PRED2(contains, replay("tianracer_yaml_syntax.yaml").error, kCorpus + "tianracer_yaml_syntax.yaml");
  EXPECT_PRED2(contains, replay("tianracer_joint_missing.yaml").error, "no_such_joint");
  EXPECT_EQ(replay("tianracer_type_not_a_string.yaml").error,
            kCorpus + "tianracer_type_not_a_string.yaml:4: controller 'wheel': type must be a string, got a dictionary");
  // The PID's checks were the only ones of a controller's keys without the YAML's place.
  EXPECT_EQ(replay("tianracer_pid_p_nan.yaml").error,
            kCorpus + "tianracer_pid_p_nan.yaml:4: controller 'left_steering_hinge_position_controller': "
            "pid/p must be finite, got nan");
  EXPECT_PRED2(contains, replay("diffbot_multiplier_nan.yaml").error,
               "wheel_separation_multiplier must be a positive number, got nan");
  EXPECT_PRED2(contains, replay("diffbot_wheel_separation_radius_zero.yaml").error,
               "wheel_separation must be positive, got 0");
  EXPECT_PRED2(contains, replay("steerbot_wheelbase_zero.yaml").error,
               "wheel_separation_h must be positive, got 0");
  // A key that is not a string: yaml-cpp's bad conversion used to escape (the process ended).
  EXPECT_EQ(replay("tianracer_fuzz_key_is_a_dictionary.yaml").error,
            kCorpus + "tianracer_fuzz_key_is_a_dictionary.yaml:13: a dictionary key must be a string, got a dictionary");
  EXPECT_EQ(replay("tianracer_key_is_a_list.yaml").error,
            kCorpus + "tianracer_key_is_a_list.yaml:3: a dictionary key must be a string, got a list");
  // 2^30 values once aliases are expanded: refused before they are.
  EXPECT_PRED2(contains, replay("tianracer_aliases_2_to_the_30.yaml").error,
               "aliases expand it to more than 1000000 values");
  // Gains of 1e308: the effort is clamped to the joint's limit, nothing overflows.
  EXPECT_EQ(replay("tianracer_pid_gains_1e308.yaml").error, "");
}

// A YAML whose top level is a list defines no controller: the robot runs without, warned.
TEST(ControllerFuzzRegressions, ATopLevelListGivesNoControllerAndAWarning) {
  const std::string file = kCorpus + "tianracer_top_level_list.yaml";
  YamlControlParams params(file);
  RobotSetupRequest request;
  request.control_config = file;
  const RobotSetup setup = setUpRobot(tianracer_sim_fuzz::controllerReplayRobot('t'), request, params);
  EXPECT_TRUE(setup.controllers.empty());
  ASSERT_EQ(setup.warnings.size(), 1u);
  EXPECT_NE(setup.warnings[0].find("its top level is not a dictionary"), std::string::npos)
      << setup.warnings[0];
  EXPECT_EQ(replay("tianracer_top_level_list.yaml").error, "");
}

}  // namespace
}  // namespace tianracer_sim
