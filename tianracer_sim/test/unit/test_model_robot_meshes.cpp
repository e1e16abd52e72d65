// readRobotMeshes (model_info): a robot's meshes read as the physics and the renderer read them,
// so that a file that would stop (or, before issue 43, crash) the simulator stops model_info
// with the same message.
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <string>
#include <vector>

#include "tianracer_sim/model/robot_meshes.h"

#include "common_test_support.h"

namespace tianracer_sim {
namespace {

using ::testing::HasSubstr;

const std::string kData = std::string(TEST_DATA_DIR) + "/";
const std::string kCycle = kData + "fuzz_regressions/mesh/collada_node_instances_itself.dae";
const std::string kGood = kData + "fuzz_regressions/mesh/collada_valid_tetrahedron.dae";

RobotModel robot(const std::string& collision, const std::string& visual) {
  LoadOptions options;
  const std::string xml =
      "<robot name='r'><link name='body'><inertial><mass value='1'/>"
      "<inertia ixx='1' ixy='0' ixz='0' iyy='1' iyz='0' izz='1'/></inertial>"
      "<visual><geometry><mesh filename='file://" + visual + "'/></geometry></visual>"
      "<collision><geometry><mesh filename='file://" + collision + "' scale='2 2 2'/></geometry></collision>"
      "</link></robot>";
  return loadRobotModel(xml, "robot_description", options);
}

TEST(RobotMeshes, AGoodRobotReadsEachFileOnce) {
  std::vector<std::string> warnings;
  EXPECT_EQ(readRobotMeshes(robot(kGood, kGood), [&](const std::string& w) { warnings.push_back(w); }), 1);
  EXPECT_TRUE(warnings.empty());
}

TEST(RobotMeshes, ACollisionMeshThatCannotBeUsedIsAnErrorNamingLinkFileAndLine) {
  // The model loader only checks that the file exists; its contents crashed assimp before.
  const RobotModel model = robot(kCycle, kGood);
  EXPECT_THAT(test::errorText<ModelError>([&] { readRobotMeshes(model, {}); }),
              HasSubstr("robot_description: link 'body' collision mesh 'file://" + kCycle + "': " + kCycle +
                        ":26: COLLADA <instance_node url='#a'>: instances a node inside itself"));
}

TEST(RobotMeshes, AVisualMeshThatCannotBeUsedIsAWarningAsTheRendererSkipsIt) {
  std::vector<std::string> warnings;
  EXPECT_EQ(readRobotMeshes(robot(kGood, kCycle), [&](const std::string& w) { warnings.push_back(w); }), 1);
  ASSERT_EQ(warnings.size(), 1u);
  EXPECT_THAT(warnings[0], HasSubstr("link 'body' visual mesh 'file://" + kCycle + "': "));
  EXPECT_THAT(warnings[0], HasSubstr("a node cycle; the renderer leaves it out"));
}

}  // namespace
}  // namespace tianracer_sim
