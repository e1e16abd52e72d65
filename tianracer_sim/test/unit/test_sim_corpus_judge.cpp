// The corpus tools' verdict logic (src/tools/corpus_judge.h, shared by model_corpus and
// world_corpus) on a shipped world and on made-up motion: the tools themselves need the mirrors
// and are run by hand (docs/gazebo_worlds.md).
#include <gtest/gtest.h>

#include <map>
#include <string>

#include "../../src/tools/corpus_judge.h"

namespace tianracer_sim {
namespace {

std::map<std::string, corpus::Judged> byName(const std::vector<corpus::Judged>& v) {
  std::map<std::string, corpus::Judged> out;
  for (const corpus::Judged& j : v) out[j.name] = j;
  return out;
}

TEST(CorpusJudge, ShippedWorldVerdicts) {
  const WorldDescription world = loadWorldFile(std::string(TEST_DATA_DIR) + "/worlds/corpus_judge.world");
  const auto judged = byName(corpus::runWorld(world, 30.0, 10.0));
  ASSERT_EQ(judged.size(), 5u);
  EXPECT_EQ(judged.at("wall").verdict, "static");
  EXPECT_EQ(judged.at("resting").verdict, "rests") << judged.at("resting").why;
  EXPECT_EQ(judged.at("stacked").verdict, "rests") << judged.at("stacked").why;
  const corpus::Judged& dropped = judged.at("dropped");
  EXPECT_EQ(dropped.verdict, "settles") << dropped.why;
  EXPECT_NEAR(dropped.X_end.translation().z(), 0.15, 0.01);  // on its base, on the ground
  EXPECT_NEAR(dropped.max_distance, 0.5, 0.02);
  EXPECT_TRUE(dropped.flat);
  const corpus::Judged& pendulum = judged.at("pendulum");
  EXPECT_TRUE(pendulum.world_joint);
  EXPECT_EQ(pendulum.verdict, "moves") << pendulum.why;
  EXPECT_NE(pendulum.why.find("joined to the world"), std::string::npos) << pendulum.why;
}

// A flat-based model still moving over the last window differs; without a flat base, or with
// plugins of its own, it moves (no verdict).
TEST(CorpusJudge, StillMovingDiffersOnlyWithAFlatBase) {
  corpus::Judged r;
  r.is_static = false;
  r.free_body = true;
  r.collisions = 1;
  r.flat = true;
  corpus::track(Eigen::Isometry3d::Identity(), false, &r);
  Eigen::Isometry3d X = Eigen::Isometry3d::Identity();
  X.translation().x() = 0.05;
  corpus::track(X, true, &r);  // 5 cm within the window
  corpus::Judged flat = r;
  corpus::judgeInWorld(&flat, 30.0, 10.0);
  EXPECT_EQ(flat.verdict, "differs");
  EXPECT_NE(flat.why.find("5.0 cm"), std::string::npos) << flat.why;
  corpus::Judged ball = r;
  ball.flat = false;
  corpus::judgeInWorld(&ball, 30.0, 10.0);
  EXPECT_EQ(ball.verdict, "moves");
  corpus::Judged driven = r;
  driven.plugins = 1;
  corpus::judgeInWorld(&driven, 30.0, 10.0);
  EXPECT_EQ(driven.verdict, "moves");
  // Moved before the window, still within it: settles.
  corpus::Judged settled = r;
  settled.window_distance = 0.002;
  corpus::judgeInWorld(&settled, 30.0, 10.0);
  EXPECT_EQ(settled.verdict, "settles");
  // No collision, static, welded: verdicts before any motion.
  corpus::Judged none;
  corpus::judgeInWorld(&none, 30.0, 10.0);
  EXPECT_EQ(none.verdict, "loads");
}

}  // namespace
}  // namespace tianracer_sim

namespace tianracer_sim {
namespace {

// model_corpus and world_corpus read an option's value through optionValue.
TEST(CorpusJudge, OptionValueTakesTheNextWordOrExitsNamingTheOption) {
  char prog[] = "tool", only[] = "--only", name[] = "box", hold[] = "--hold";
  char* argv[] = {prog, only, name, hold};
  int i = 1;
  EXPECT_EQ(corpus::optionValue(4, argv, &i), "box");
  EXPECT_EQ(i, 2);
  i = 3;
  EXPECT_EXIT(corpus::optionValue(4, argv, &i), ::testing::ExitedWithCode(2), "--hold needs a value");
}

}  // namespace
}  // namespace tianracer_sim
