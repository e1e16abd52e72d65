// Which frame a robot's camera images are stamped in (sensors/optical_frame.h): the plugin's
// frameName when the URDF makes it an optical link at the camera (TurtleBot3's
// camera_rgb_optical_frame), else "<frameName>_optical_frame", which the node adds on TF.
#include <gtest/gtest.h>

#include <memory>
#include <string>

#include "tianracer_sim/simulator/sim_sensors.h"
#include "tianracer_sim/simulator/simulator.h"
#include "tianracer_sim/world/world.h"

namespace tianracer_sim {
namespace {

std::string camera(const std::string& name, const std::string& frame, const std::string& type) {
  const std::string plugin = type == "depth" ? "libgazebo_ros_openni_kinect.so"
                                             : "libgazebo_ros_camera.so";
  return "<gazebo reference='camera_frame'><sensor type='" + type + "' name='" + name +
         "'><camera><horizontal_fov>1</horizontal_fov><image><width>32</width>"
         "<height>24</height></image></camera><plugin name='p' filename='" + plugin +
         "'><cameraName>" + name + "</cameraName><frameName>" + frame +
         "</frameName></plugin></sensor></gazebo>";
}

TEST(SimulatorCameraFrames, AnOpticalLinkOfTheUrdfIsUsedAsItIs) {
  const std::string urdf =
      R"(<robot name="r">
  <link name="base_link"><inertial><mass value="1"/>
    <inertia ixx="0.01" iyy="0.01" izz="0.01" ixy="0" ixz="0" iyz="0"/></inertial>
    <collision><geometry><box size="0.2 0.2 0.1"/></geometry></collision></link>
  <link name="camera_frame"/><link name="camera_optical_frame"/><link name="camera_turned"/>
  <joint name="c" type="fixed"><parent link="base_link"/><child link="camera_frame"/>
    <origin xyz="0.1 0 0.1"/></joint>
  <joint name="o" type="fixed"><parent link="camera_frame"/><child link="camera_optical_frame"/>
    <origin rpy="-1.57 0 -1.57"/></joint>
  <joint name="t" type="fixed"><parent link="camera_frame"/><child link="camera_turned"/>
    <origin rpy="0 0 -1.57"/></joint>)" +
      camera("optical", "camera_optical_frame", "camera") +
      camera("plain", "camera_frame", "camera") + camera("turned", "camera_turned", "camera") +
      camera("depth", "camera_optical_frame", "depth") + "</robot>";
  Simulator sim(loadWorldString("<sdf version='1.6'><world name='w'><include>"
                                "<uri>model://ground_plane</uri></include></world></sdf>",
                                "w.world", "."),
                {});
  RobotSpawn spawn;
  spawn.name = "r";
  spawn.model = loadRobotModel(urdf, "r", LoadOptions());
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
