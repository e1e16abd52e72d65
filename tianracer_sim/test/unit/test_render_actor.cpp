// A camera sees an <actor>'s link visual where its script puts it (docs/actors.md): the depth at
// the image centre as the actor walks across the view. Sim time only.
#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "tianracer_sim/render/camera_intrinsics.h"
#include "tianracer_sim/render/renderer.h"
#include "tianracer_sim/world/world.h"

namespace tianracer_sim {
namespace {

TEST(RenderActor, TheCameraSeesTheActorWhereItsScriptPutsIt) {
  // A visual-only box (as Gazebo's animated_box.world) walks along y through x = 3 in 4 s.
  const WorldDescription world = loadWorldString(
      "<sdf version='1.6'><world name='w'><actor name='walker'><pose>0 9 0 0 0 0</pose>"
      "<link name='body'><pose>0 0 1 0 0 0</pose><visual name='v'><geometry><box>"
      "<size>0.4 0.4 2</size></box></geometry></visual></link><script><loop>false</loop>"
      "<trajectory id='0' type='walk'>"
      "<waypoint><time>0</time><pose>3 -2 0 0 0 0</pose></waypoint>"
      "<waypoint><time>4</time><pose>3 2 0 0 0 0</pose></waypoint>"
      "</trajectory></script></actor></world></sdf>",
      "actor.world", ".");
  Scene scene;
  addToScene(world, scene);
  std::vector<ActorPlayer> players = actorPlayers(world, 0.001);
  Renderer renderer;
  const int W = 16, H = 16;
  const CameraIntrinsics K = CameraIntrinsics::fromHorizontalFov(W, H, 0.2, 0.05, 20.0);
  std::vector<float> depth(W * H);
  const Eigen::Isometry3d X_WC(Eigen::Translation3d(0, 0, 1));  // looking along +x
  auto centreDepth = [&](double t) {
    updateActorScene(world, &players, t, &scene);
    renderer.renderView(scene, X_WC, K, nullptr, depth.data());
    return depth[(H / 2) * W + W / 2];
  };
  EXPECT_TRUE(std::isinf(centreDepth(0.0)));  // at its <pose>, y 9
  EXPECT_TRUE(std::isinf(centreDepth(0.5)));  // y near -1.8
  EXPECT_NEAR(centreDepth(2.0), 2.8, 1e-3);   // in the view: its near face
  EXPECT_TRUE(std::isinf(centreDepth(3.9)));  // past
}

}  // namespace
}  // namespace tianracer_sim
