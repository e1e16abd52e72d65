// Which frame a robot's camera images are stamped in (plugins/camera/optical_frame.h): the plugin's
// frameName when the URDF makes it an optical link at the camera (TurtleBot3's
// camera_rgb_optical_frame), else "<frameName>_optical_frame", which the node adds on TF
// (test/data/urdf/camera_frames.urdf).
#include <gtest/gtest.h>

#include <memory>
#include <string>

#include "tianracer_sim/plugins/camera/sim_camera.h"
#include "tianracer_sim/simulator/simulator.h"
#include "tianracer_sim/world/world.h"

namespace tianracer_sim {
namespace {

TEST(SimulatorCameraFrames, AnOpticalLinkOfTheUrdfIsUsedAsItIs) {
  Simulator sim(loadWorldString("<sdf version='1.6'><world name='w'><include>"
                                "<uri>model://ground_plane</uri></include></world></sdf>",
                                "w.world", "."),
                {});
  RobotSpawn spawn;
  spawn.name = "r";
  spawn.model =
      loadRobotModelFile(std::string(TEST_DATA_DIR) + "/urdf/camera_frames.urdf", LoadOptions());
  spawn.tf_prefix = "r2";
  const ModelId id = sim.addRobot(std::move(spawn));
  const auto frameOf = [&](const std::string& name) {
    const SimSensor* s = sim.findSensor(id, name);
    if (const auto* c = dynamic_cast<const SimCamera*>(s)) return c->camera().config().opticalFrame();
    if (const auto* d = dynamic_cast<const SimDepthCamera*>(s))
      return d->camera().config().camera.opticalFrame();
    return std::string("(no camera '" + name + "')");
  };
  // The URDF's own optical link (with the robot's tf_prefix, as every frame of it).
  EXPECT_EQ(frameOf("optical"), "r2/camera_optical_frame");
  EXPECT_EQ(frameOf("depth"), "r2/camera_optical_frame");
  // The camera's plain link, and a link turned some other way: an optical frame is added.
  EXPECT_EQ(frameOf("plain"), "r2/camera_frame_optical_frame");
  EXPECT_EQ(frameOf("turned"), "r2/camera_turned_optical_frame");
}

}  // namespace
}  // namespace tianracer_sim
