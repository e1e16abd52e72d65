// <collide_bitmask> and <collide_without_contact_bitmask> as Gazebo filters collisions
// (gazebo/physics/ode/ODEPhysics.cc, ODEPhysics::Collide): two collisions meet only when their
// collide masks share a bit; with collide_without_contact on either side, only when their
// without-contact masks do. After Gazebo's worlds/shapes_bitmask.world.
#include <gtest/gtest.h>

#include <string>
#include <vector>

#include "tianracer_sim/common/diagnostic.h"
#include "tianracer_sim/plugins/bumper/sim_bumper.h"
#include "tianracer_sim/simulator/simulator.h"
#include "tianracer_sim/world/world.h"

namespace tianracer_sim {
namespace {

std::string box(const std::string& name, double z, const std::string& contact) {
  return "<model name='" + name + "'><pose>0 0 " + std::to_string(z) +
         " 0 0 0</pose><link name='link'><inertial><mass>1</mass><inertia><ixx>0.17</ixx>"
         "<iyy>0.17</iyy><izz>0.17</izz></inertia></inertial><collision name='c'><geometry><box>"
         "<size>1 1 1</size></box></geometry><surface><contact>" + contact +
         "</contact></surface></collision></link></model>";
}

std::string world(const std::string& models) {
  return "<sdf version='1.6'><world name='w'><include><uri>model://ground_plane</uri></include>" +
         models + "</world></sdf>";
}

class WantsAll : public SensorListener {
 public:
  SensorOutputs wanted(const SimSensor&, SensorOutputs due) override { return due; }
  void onOutputs(const SimSensor&, SensorOutputs, double) override {}
};

double height(const Simulator& sim, const std::string& model) {
  return sim.modelState(sim.findModel(model)).X_WE.translation().z();
}

TEST(CollideBitmask, BoxesMeetOnlyWhenTheirMasksShareABit) {
  // shapes_bitmask.world: A (0x01) rests on the ground (0xffff); B (0x02) falls through A on to
  // the ground; C (0x03) meets both and rests on top of them.
  std::vector<std::string> warnings;
  SimulatorOptions options;
  options.log.warn = [&](const std::string& w) { warnings.push_back(w); };
  Simulator sim(loadWorldString(world(box("a", 1.0, "<collide_bitmask>0x01</collide_bitmask>") +
                                      box("b", 3.0, "<collide_bitmask>0x02</collide_bitmask>") +
                                      box("c", 6.0, "<collide_bitmask>3</collide_bitmask>")),
                                "shapes_bitmask.world", "."),
                options);
  EXPECT_TRUE(warnings.empty()) << ::testing::PrintToString(warnings);
  sim.step(4000);
  EXPECT_NEAR(height(sim, "a"), 0.5, 0.01);
  EXPECT_NEAR(height(sim, "b"), 0.5, 0.01);  // inside A, on the ground
  EXPECT_NEAR(height(sim, "c"), 1.5, 0.01);  // on A and B
}

TEST(CollideBitmask, WithoutContactOnAMovingBodyMeetsNothingItsMaskExcludes) {
  // A moving box that collides without contact pushes nothing: it falls through a static pad
  // and the ground, and the pad's bumper sees it pass. A second one's without-contact mask (2)
  // shares no bit with the pad's default (1): Gazebo makes no contact at all, the bumper never
  // sees it.
  Simulator sim(
      loadWorldString(
          world("<model name='pad'><static>true</static><pose>0 0 0.5 0 0 0</pose><link name='link'>"
                "<collision name='c'><geometry><box><size>4 2 1</size></box></geometry>"
                "</collision><sensor name='pad_bumper' type='contact'><update_rate>100</update_rate>"
                "<contact><collision>c</collision></contact><plugin name='b' "
                "filename='libgazebo_ros_bumper.so'><bumperTopicName>pad_bumper</bumperTopicName>"
                "<frameName>world</frameName></plugin></sensor></link></model>" +
                box("ghost", 2.0, "<collide_without_contact>true</collide_without_contact>") +
                box("masked", 2.0, "<collide_without_contact>true</collide_without_contact>"
                                   "<collide_without_contact_bitmask>2</collide_without_contact_bitmask>")),
          "ghost.world", "."),
      {});
  sim.attachWorldSensors([](SimSensor& s) { s.setListener(std::make_unique<WantsAll>()); });
  const auto* bumper = dynamic_cast<const SimBumper*>(sim.findSensor(sim.findModel("pad"), "pad_bumper"));
  ASSERT_NE(bumper, nullptr);
  bool ghost_seen = false, masked_seen = false;
  for (int i = 0; i < 100; ++i) {
    sim.step(10);
    for (const BumperState& s : bumper->states()) {
      ghost_seen = ghost_seen || s.collision2.rfind("ghost::", 0) == 0;
      masked_seen = masked_seen || s.collision2.rfind("masked::", 0) == 0;
    }
  }
  EXPECT_LT(height(sim, "ghost"), -2.0);
  EXPECT_LT(height(sim, "masked"), -2.0);
  EXPECT_TRUE(ghost_seen) << "the pad's bumper never saw the box pass through it";
  EXPECT_FALSE(masked_seen);
}

TEST(CollideBitmask, ABadMaskIsAnErrorNamingTheElement) {
  for (const std::string& text : {"-1", "0x1g", "0x100000000", "1.5", ""}) {
    try {
      loadWorldString(world(box("a", 1.0, "<collide_bitmask>" + text + "</collide_bitmask>")),
                      "bad_mask.world", ".");
      ADD_FAILURE() << "accepted <collide_bitmask>" << text;
    } catch (const InputError& e) {
      const std::string what = e.what();
      EXPECT_NE(what.find("bad_mask.world:1:"), std::string::npos) << what;
      EXPECT_NE(what.find("collide_bitmask"), std::string::npos) << what;
      EXPECT_NE(what.find("'" + text + "' is not an unsigned integer"), std::string::npos) << what;
    }
  }
}

}  // namespace
}  // namespace tianracer_sim
