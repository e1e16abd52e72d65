// The regression corpus of issue 43 (test/data/fuzz_regressions/{model,world}/): every file
// that once crashed, hung, blew up or left non-finite state. Each is replayed as the simulator
// uses it: loaded, built into the physics and the ray-casting scene, stepped 200 times with a
// ray fan cast every 20 steps, with the fuzz harness's checks (fuzz/sim_replay.h). It must either stay finite throughout, or end in a clean error
// (InputError / PhysicsError / MeshError) that names its file; nothing may crash or hang.
// The comment at the top of each file says what it once did.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <string>
#include <vector>

#include "../../fuzz/sim_replay.h"
#include "sim_test_support.h"
#include "tianracer_sim/world/world.h"

namespace tianracer_sim {
namespace {

namespace fs = std::filesystem;

const std::string kCorpus = std::string(TEST_DATA_DIR) + "/fuzz_regressions";
constexpr int kSteps = 200;

std::vector<std::string> corpus(const std::string& kind) {
  std::vector<std::string> files;
  for (const auto& e : fs::directory_iterator(kCorpus + "/" + kind)) files.push_back(e.path().string());
  std::sort(files.begin(), files.end());
  return files;
}

/// What happened to one file: "" (loaded, stayed finite), or the clean error's text.
struct Outcome {
  std::string error;
  std::vector<std::string> warnings;
};

/// The harness's checks (fuzz/sim_replay.h), here with 360 rays every 20 steps.
const tianracer_sim_fuzz::SimReplay kReplay{kSteps, 20, 360};

Outcome replayModel(const std::string& file) {
  Outcome out;
  const WarningSink warn = [&](const std::string& w) { out.warnings.push_back(w); };
  try {
    LoadOptions options;
    options.warn = warn;
    RobotConfig config;
    config.name = "cart";
    config.model = loadRobotModelFile(file, options);
    config.X_WB_spawn.translation() = Eigen::Vector3d(0, 0, 0.2);
    EXPECT_EQ(tianracer_sim_fuzz::replayRobot(std::move(config), test::groundWorld(), warn, kReplay), "")
        << file;
  } catch (const InputError& e) {
    out.error = e.what();
  } catch (const PhysicsError& e) {
    out.error = e.what();
  }
  return out;
}

Outcome replayWorld(const std::string& file) {
  Outcome out;
  const WarningSink warn = [&](const std::string& w) { out.warnings.push_back(w); };
  try {
    WorldLoadOptions options;
    options.warn = warn;
    EXPECT_EQ(tianracer_sim_fuzz::replayWorld(loadWorldFile(file, options), warn, kReplay), "") << file;
  } catch (const InputError& e) {
    out.error = e.what();
  } catch (const PhysicsError& e) {
    out.error = e.what();
  }
  return out;
}

/// An error must start with the file and a line ("<file>...:<line>: ").
void expectPlaced(const std::string& file, const std::string& error) {
  EXPECT_EQ(error.rfind(file, 0), 0u) << error;
  const std::string rest = error.substr(std::min(error.size(), file.size()));
  EXPECT_TRUE(rest.size() > 1 && rest[0] == ':' && std::isdigit(static_cast<unsigned char>(rest[1])))
      << "no line: " << error;
}

/// Every file of corpus/<kind> through `replay`: it loads and stays finite, or its error is placed.
void expectEveryFileFiniteOrPlaced(const std::string& kind, Outcome (*replay)(const std::string&)) {
  const std::vector<std::string> files = corpus(kind);
  ASSERT_GE(files.size(), 10u);
  for (const std::string& f : files) {
    SCOPED_TRACE(f);
    const Outcome o = replay(f);
    if (!o.error.empty()) expectPlaced(f, o.error);
    if (::testing::Test::HasFailure()) return;
  }
}

TEST(FuzzRegressions, EveryModelLoadsAndStaysFiniteOrIsACleanErrorWithFileAndLine) {
  expectEveryFileFiniteOrPlaced("model", replayModel);
}

TEST(FuzzRegressions, EveryWorldLoadsAndStaysFiniteOrIsACleanErrorWithFileAndLine) {
  expectEveryFileFiniteOrPlaced("world", replayWorld);
}

// What each case must give: refused with the bound in the message, or loaded.
TEST(FuzzRegressions, EachCaseGivesItsMessage) {
  const auto model = [](const std::string& name) { return replayModel(kCorpus + "/model/" + name + ".urdf"); };
  const auto world = [](const std::string& name) { return replayWorld(kCorpus + "/world/" + name + ".world"); };
  const auto contains = [](const std::string& error, const std::string& text) {
    return error.find(text) != std::string::npos;
  };
  EXPECT_PRED2(contains, model("joint_origin_1e30").error, "joint 'wheel_joint': <origin xyz='1e30 0.12 0.05'>: x 1e+30 is out of range (|x| <= 1e+06 m)");
  EXPECT_PRED2(contains, model("joint_origin_2_1e9").error, "x 2.1e+09 is out of range");
  EXPECT_PRED2(contains, model("inertial_origin_1e30").error, "link 'base_link': <inertial> <origin xyz='0 1e30 0'>: y 1e+30 is out of range");
  EXPECT_PRED2(contains, model("mass_1e308").error, "mass 1e308 is out of range (<= 1e+09 kg)");
  EXPECT_PRED2(contains, model("box_1e308").error, "<box size='1e308 0.2 0.1'> is out of range (<= 1e+06 m)");
  EXPECT_PRED2(contains, model("damping_1e308").error, "<dynamics damping='1e308'> must be finite, >= 0 and <= 1e+06");
  EXPECT_EQ(model("axis_overflow").error, "");  // loads: the axis is (1 1 0) / sqrt(2)
  EXPECT_PRED2(contains, model("axis_zero").error, "<axis xyz='0 0 0'> must be finite and not zero");
  EXPECT_PRED2(contains, model("inertia_1e300").error, "inertia ixx=1e300 is out of range");
  EXPECT_EQ(model("rpy_large").error, "");
  EXPECT_EQ(model("damping_3_light_wheel").error, "");
  const Outcome tri = model("triangle_inequality");
  EXPECT_EQ(tri.error, "");
  bool warned = false;
  for (const auto& w : tri.warnings) warned = warned || w.find("violate the triangle inequality") != std::string::npos;
  EXPECT_TRUE(warned);
  EXPECT_PRED2(contains, model("moving_link_without_mass").error, "link 'wheel' (child of joint 'wheel_joint'): a moving body needs a positive mass");

  EXPECT_PRED2(contains, world("pose_nan").error, "model 'crate': <pose> 'nan 0 0.5 0 0 0' is not finite");
  EXPECT_PRED2(contains, world("pose_neg_inf").error, "is not finite");
  EXPECT_PRED2(contains, world("pose_1e30").error, "model 'crate': <pose> position x 1e+30 is out of range (|x| <= 1e+06 m)");
  EXPECT_PRED2(contains, world("size_nan").error, "is not finite");
  EXPECT_PRED2(contains, world("size_1e308").error, "<box> <size> x 1e+308 is out of range (|x| <= 1e+06 m)");
  EXPECT_PRED2(contains, world("radius_inf").error, "is not finite");
  EXPECT_PRED2(contains, world("radius_neg_inf").error, "is not finite");
  EXPECT_PRED2(contains, world("gravity_1e308").error, "<physics>: <gravity> z -1e+308 is out of range (|z| <= 1000 m/s^2)");
  EXPECT_PRED2(contains, world("max_step_size_1e308").error, "<max_step_size> 1e308 is out of range (0 < step <= 0.1 s)");
  EXPECT_PRED2(contains, world("damping_1e308").error, "<damping> 1e308 is out of range (<= 1e+06)");
  EXPECT_EQ(world("axis_overflow").error, "");
  EXPECT_EQ(world("damping_3_light_lid").error, "");
  // A world model's bad mass is reported and the model held static (the world loads).
  const Outcome heavy = world("mass_1e308");
  EXPECT_EQ(heavy.error, "");
  bool held = false;
  for (const auto& w : heavy.warnings) held = held || w.find("<mass> 1e+308 is out of range (<= 1e+09 kg)") != std::string::npos;
  EXPECT_TRUE(held);
}

}  // namespace
}  // namespace tianracer_sim
