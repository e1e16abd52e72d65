// What gazebo_ros's property services change in the Simulator (simulator/properties.cpp):
// physics (step, gravity, solver), joints of world models (get/set_joint_properties,
// set_model_configuration), link inertials and the world's lights; and that bad input is
// refused naming it, with nothing changed.
#include <gtest/gtest.h>

#include <cmath>
#include <functional>
#include <iostream>
#include <limits>
#include <string>

#include "tianracer_sim/plugins/bumper/sim_bumper.h"
#include "tianracer_sim/plugins/camera/sim_camera.h"
#include "tianracer_sim/plugins/imu/sim_imu.h"
#include "tianracer_sim/simulator/simulator.h"
#include "tianracer_sim/world/world.h"

namespace tianracer_sim {
namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

/// A pendulum hinged to the world about x (bob 0.5 m below the pivot at z = 3), a free box
/// resting on the ground, a static wall, the sun and a point light 2 m up.
WorldDescription propertiesWorld() {
  return loadWorldString(
      "<sdf version='1.6'><world name='w'>"
      "<include><uri>model://ground_plane</uri></include><include><uri>model://sun</uri></include>"
      "<light name='lamp' type='point'><pose>0 0 2 0 0 0</pose><diffuse>1 0.5 0.25 1</diffuse>"
      "<attenuation><constant>0.5</constant><linear>0.5</linear><quadratic>0.25</quadratic>"
      "</attenuation></light>"
      "<model name='pendulum'><pose>0 0 3 0 0 0</pose>"
      "<link name='bob'><pose>0 0 -0.5 0 0 0</pose><inertial><pose>0 0 0.01 0 0 0</pose>"
      "<mass>1.5</mass><inertia><ixx>0.002</ixx><iyy>0.003</iyy><izz>0.004</izz></inertia>"
      "</inertial><collision name='c'><geometry><sphere><radius>0.05</radius></sphere>"
      "</geometry></collision></link>"
      "<joint name='pivot' type='revolute'><parent>world</parent><child>bob</child>"
      "<pose>0 0 0.5 0 0 0</pose><axis><xyz>1 0 0</xyz><limit><lower>-1</lower><upper>1</upper>"
      "</limit></axis></joint></model>"
      "<model name='box'><pose>2 0 0.1 0 0 0</pose><link name='link'><inertial><mass>1</mass>"
      "<inertia><ixx>0.01</ixx><iyy>0.01</iyy><izz>0.01</izz></inertia></inertial>"
      "<collision name='c'><geometry><box><size>0.2 0.2 0.2</size></box></geometry></collision>"
      "</link></model>"
      "<model name='wall'><static>true</static><pose>0 5 0.5 0 0 0</pose><link name='link'>"
      "<collision name='c'><geometry><box><size>1 0.1 1</size></box></geometry></collision>"
      "</link></model>"
      "</world></sdf>",
      "properties.world", ".");
}

double boxZ(const Simulator& sim) { return sim.modelState(sim.findModel("box")).X_WE.translation().z(); }

TEST(SimulatorProperties, PhysicsStepAndGravityChangeTheSimulation) {
  Simulator sim(propertiesWorld(), {});
  PhysicsProperties p = sim.properties().physicsProperties();
  EXPECT_DOUBLE_EQ(p.time_step, 0.001);
  EXPECT_DOUBLE_EQ(p.max_update_rate, 1000.0);  // real_time_factor 1 at 1 ms
  EXPECT_DOUBLE_EQ(p.gravity.z(), -9.8);
  EXPECT_EQ(p.solver_iterations, 20);
  // Without gravity, the box lifted 1 m stays where it is; with it, it falls.
  p.gravity = Eigen::Vector3d::Zero();
  sim.properties().setPhysicsProperties(p);
  PhysicsRobot& box = *sim.physicsOf(sim.findModel("box"));
  box.setBasePose(Eigen::Isometry3d(Eigen::Translation3d(2.0, 0.0, 1.1)));
  const double z0 = boxZ(sim);
  sim.step(300);
  EXPECT_NEAR(boxZ(sim), 1.1, 1e-9);
  // A 2 ms step from now on: 100 steps are 0.2 s more, the 0.3 s run stays.
  p.time_step = 0.002;
  p.gravity = Eigen::Vector3d(0, 0, -9.8);
  p.max_update_rate = 250.0;
  p.solver_iterations = 30;
  sim.properties().setPhysicsProperties(p);
  EXPECT_DOUBLE_EQ(sim.dt(), 0.002);
  EXPECT_DOUBLE_EQ(sim.properties().maxUpdateRate(), 250.0);
  EXPECT_EQ(sim.properties().physicsProperties().solver_iterations, 30);
  sim.step(100);
  EXPECT_NEAR(sim.time(), 0.5, 1e-9);
  // Free fall for 0.2 s: 0.5 g t^2 = 0.196 m.
  EXPECT_NEAR(z0 - boxZ(sim), 0.5 * 9.8 * 0.2 * 0.2, 0.005);
  std::cout << "[set_physics_properties] box z " << z0 << " m after 0.3 s without gravity, "
            << boxZ(sim) << " m after 0.2 s more with it\n";
}

/// Wants every output of the sensors it listens to.
class WantsAll : public SensorListener {
 public:
  SensorOutputs wanted(const SimSensor&, SensorOutputs due) override { return due; }
  void onOutputs(const SimSensor&, SensorOutputs, double) override {}
};

/// A contact sensor with gazebo_ros_bumper on link 'link' of a world model.
std::string bumperSensor(const std::string& name) {
  return "<sensor name='" + name + "' type='contact'><update_rate>100</update_rate><contact>"
         "<collision>c</collision></contact><plugin name='b' filename='libgazebo_ros_bumper.so'>"
         "<bumperTopicName>" + name + "</bumperTopicName><frameName>world</frameName></plugin>"
         "</sensor>";
}

TEST(SimulatorProperties, BumpersAndAnImuFollowANewStepAndGravity) {
  // A 1 kg box at rest on a static pad, each with a bumper on its collision, and an IMU on the
  // box: the pad holds the box with m g, and the IMU feels -g. After set_physics_properties
  // doubles the step and changes gravity, they read the new values (a bumper's force is
  // impulse / the step now in force; Gazebo's ImuSensor reads the gravity at each update).
  SimulatorOptions options;
  Simulator sim(
      loadWorldString(
          "<sdf version='1.6'><world name='w'><include><uri>model://ground_plane</uri></include>"
          "<model name='pad'><static>true</static><pose>0 0 0.05 0 0 0</pose><link name='link'>"
          "<collision name='c'><geometry><box><size>1 1 0.1</size></box></geometry></collision>" +
              bumperSensor("pad_bumper") +
              "</link></model>"
              "<model name='box'><pose>0 0 0.2 0 0 0</pose><link name='link'><inertial>"
              "<mass>1</mass><inertia><ixx>0.01</ixx><iyy>0.01</iyy><izz>0.01</izz></inertia>"
              "</inertial><collision name='c'><geometry><box><size>0.2 0.2 0.2</size></box>"
              "</geometry></collision>" +
              bumperSensor("box_bumper") +
              "<sensor name='imu' type='imu'><update_rate>100</update_rate>"
              "<plugin name='i' filename='libgazebo_ros_imu_sensor.so'><topicName>imu</topicName>"
              "<bodyName>link</bodyName><frameName>link</frameName><updateRateHZ>100</updateRateHZ>"
              "<gaussianNoise>0</gaussianNoise></plugin></sensor>"
              "</link></model></world></sdf>",
          "bumper_imu.world", "."),
      options);
  sim.attachWorldSensors([](SimSensor& s) { s.setListener(std::make_unique<WantsAll>()); });
  const ModelId box = sim.findModel("box");
  const auto* box_bumper = dynamic_cast<const SimBumper*>(sim.findSensor(box, "box_bumper"));
  const auto* pad_bumper =
      dynamic_cast<const SimBumper*>(sim.findSensor(sim.findModel("pad"), "pad_bumper"));
  const auto* imu = dynamic_cast<const SimImu*>(sim.findSensor(box, "imu"));
  ASSERT_NE(box_bumper, nullptr);
  ASSERT_NE(pad_bumper, nullptr);
  ASSERT_NE(imu, nullptr);
  const auto held = [](const SimBumper* bumper) {
    Eigen::Vector3d f = Eigen::Vector3d::Zero();
    for (const BumperState& s : bumper->states()) f += s.total_force;
    return f.norm();
  };
  sim.step(1000);
  EXPECT_NEAR(held(box_bumper), 9.8, 0.3);
  EXPECT_NEAR(held(pad_bumper), 9.8, 0.3);
  ASSERT_EQ(pad_bumper->states().size(), 1u);
  EXPECT_EQ(pad_bumper->states()[0].collision1, "pad::link");  // model::link (docs)
  EXPECT_EQ(pad_bumper->states()[0].collision2, "box::link");
  EXPECT_NEAR(imu->reading().linear_acceleration.z(), 9.8, 0.3);

  PhysicsProperties p = sim.properties().physicsProperties();
  p.time_step = 0.002;
  p.max_update_rate = 500.0;
  p.gravity = Eigen::Vector3d(0.0, 0.0, -5.0);
  sim.properties().setPhysicsProperties(p);
  sim.step(500);
  EXPECT_NEAR(held(box_bumper), 5.0, 0.2);
  EXPECT_NEAR(held(pad_bumper), 5.0, 0.2);
  EXPECT_NEAR(imu->reading().linear_acceleration.z(), 5.0, 0.2);
}

TEST(SimulatorProperties, ACollisionWithoutContactIsTouchedButPushesNothing) {
  // Gazebo's mud.world: a static mud pit with <collide_without_contact> and a contact sensor.
  // A crate dropped through it falls on to the ground; the pit's bumper sees it pass.
  SimulatorOptions options;
  std::vector<std::string> warnings;
  options.log.warn = [&](const std::string& w) { warnings.push_back(w); };
  Simulator sim(
      loadWorldString(
          "<sdf version='1.6'><world name='w'><include><uri>model://ground_plane</uri></include>"
          "<model name='mud'><static>true</static><pose>0 0 0.5 0 0 0</pose><link name='link'>"
          "<collision name='c'><geometry><box><size>1 1 0.2</size></box></geometry><surface>"
          "<contact><collide_without_contact>true</collide_without_contact></contact></surface>"
          "</collision>" +
              bumperSensor("mud_bumper") +
              "</link></model>"
              "<model name='crate'><pose>0 0 1 0 0 0</pose><link name='link'><inertial>"
              "<mass>1</mass><inertia><ixx>0.01</ixx><iyy>0.01</iyy><izz>0.01</izz></inertia>"
              "</inertial><collision name='c'><geometry><box><size>0.2 0.2 0.2</size></box>"
              "</geometry></collision></link></model>"
              // On a link that moves, as in Gazebo: it meets nothing, not even the ground.
              "<model name='floater'><pose>3 0 0.1 0 0 0</pose><link name='link'><inertial>"
              "<mass>1</mass><inertia><ixx>0.01</ixx><iyy>0.01</iyy><izz>0.01</izz></inertia>"
              "</inertial><collision name='c'><geometry><box><size>0.2 0.2 0.2</size></box>"
              "</geometry><surface><contact><collide_without_contact>1</collide_without_contact>"
              "</contact></surface></collision></link></model></world></sdf>",
          "mud.world", "."),
      options);
  sim.attachWorldSensors([](SimSensor& s) { s.setListener(std::make_unique<WantsAll>()); });
  EXPECT_TRUE(warnings.empty()) << ::testing::PrintToString(warnings);
  const auto* mud = dynamic_cast<const SimBumper*>(sim.findSensor(sim.findModel("mud"), "mud_bumper"));
  ASSERT_NE(mud, nullptr);
  bool seen = false;
  for (int i = 0; i < 200; ++i) {
    sim.step(10);
    for (const BumperState& s : mud->states()) seen = seen || s.collision2 == "crate::link";
  }
  EXPECT_TRUE(seen) << "the pit's bumper never saw the crate pass";
  EXPECT_NEAR(sim.modelState(sim.findModel("crate")).X_WE.translation().z(), 0.1, 2e-3);
  EXPECT_TRUE(mud->states().empty());  // the crate is through, on the ground
  // 2 s of free fall from 0.1 m: through the ground plane.
  EXPECT_LT(sim.modelState(sim.findModel("floater")).X_WE.translation().z(), -15.0);
}

TEST(SimulatorProperties, BadPhysicsIsRefusedAndChangesNothing) {
  Simulator sim(propertiesWorld(), {});
  const PhysicsProperties before = sim.properties().physicsProperties();
  auto refused = [&](PhysicsProperties p, const std::string& text) {
    try {
      sim.properties().setPhysicsProperties(p);
      ADD_FAILURE() << "accepted: " << text;
    } catch (const InputError& e) {
      EXPECT_NE(std::string(e.what()).find(text), std::string::npos) << e.what();
    }
    const PhysicsProperties now = sim.properties().physicsProperties();
    EXPECT_EQ(now.time_step, before.time_step);
    EXPECT_EQ(now.gravity, before.gravity);
    EXPECT_EQ(now.max_update_rate, before.max_update_rate);
    EXPECT_EQ(now.solver_iterations, before.solver_iterations);
  };
  PhysicsProperties p = before;
  p.time_step = -0.001;
  refused(p, "time_step must be in (0, 0.1] s, got -0.001");
  p = before;
  p.time_step = kNaN;
  refused(p, "time_step");
  p = before;
  p.gravity.x() = kNaN;
  p.time_step = 0.002;  // a good field alongside a bad one is not applied either
  refused(p, "gravity (nan, 0, -9.8) must be finite");
  p = before;
  p.max_update_rate = -1.0;
  refused(p, "max_update_rate must be finite and >= 0");
  p = before;
  p.solver_iterations = 0;
  refused(p, "sor_pgs_iters (solver iterations) must be in [1, 10000], got 0");
  p = before;
  p.auto_disable_bodies = !before.auto_disable_bodies;
  refused(p, "auto_disable_bodies cannot be changed");
}

TEST(SimulatorProperties, JointsOfWorldModelsAreReadAndSet) {
  Simulator sim(propertiesWorld(), {});
  JointProperties j = sim.properties().jointProperties("pivot");
  EXPECT_EQ(j.model, "pendulum");
  EXPECT_EQ(j.info.type, JointType::kRevolute);
  EXPECT_EQ(sim.properties().jointProperties("pendulum::pivot").info.name, "pivot");
  // set_model_configuration: the pendulum at 0.5 rad, at rest; then it swings down.
  sim.properties().setModelConfiguration("pendulum", {"pivot"}, {0.5});
  j = sim.properties().jointProperties("pivot");
  EXPECT_DOUBLE_EQ(j.position, 0.5);
  EXPECT_DOUBLE_EQ(j.rate, 0.0);
  sim.step(100);
  EXPECT_LT(sim.properties().jointProperties("pivot").position, 0.5);
  EXPECT_LT(sim.properties().jointProperties("pivot").rate, 0.0);
  // Damping, limits, a velocity with its force cap.
  JointPropertiesChange c;
  c.damping = 0.7;
  c.lower = -0.2;
  c.upper = 0.3;
  sim.properties().setJointProperties("pendulum::pivot", c);
  j = sim.properties().jointProperties("pivot");
  EXPECT_DOUBLE_EQ(j.info.damping, 0.7);
  EXPECT_DOUBLE_EQ(j.info.lower, -0.2);
  EXPECT_DOUBLE_EQ(j.info.upper, 0.3);
  JointPropertiesChange v;
  v.velocity = 0.5;
  v.fmax = 100.0;
  sim.properties().setModelConfiguration("pendulum", {"pivot"}, {0.0});
  sim.properties().setJointProperties("pivot", v);
  sim.step(100);
  EXPECT_NEAR(sim.properties().jointProperties("pivot").rate, 0.5, 0.02);
}

// apply_joint_effort's core: an effort added to the joint, every step until replaced.
TEST(SimulatorProperties, JointExternalEffortPushesUntilReplaced) {
  Simulator sim(propertiesWorld(), {});
  PhysicsProperties p = sim.properties().physicsProperties();
  p.gravity = Eigen::Vector3d::Zero();
  sim.properties().setPhysicsProperties(p);
  const JointRef joint = sim.entities().joint("pivot");
  PhysicsRobot& pendulum = *joint.body;
  const int i = joint.index;
  pendulum.setJointExternalEffort(i, 0.1);
  sim.step(100);
  // About the pivot: I = m L^2 + ixx = 1.5 * 0.25 + 0.002 (the bob's inertial is 1 cm up).
  const double rate = sim.properties().jointProperties("pivot").rate;
  EXPECT_GT(rate, 0.0);
  EXPECT_NEAR(rate, 0.1 * 0.1 / (1.5 * 0.49 * 0.49 + 0.002), 0.1 * rate);
  pendulum.setJointExternalEffort(i, 0.0);
  sim.step(100);
  EXPECT_NEAR(sim.properties().jointProperties("pivot").rate, rate, 1e-6 + 1e-3 * rate);
  pendulum.setJointExternalEffort(i, kNaN);  // rejected, counted
  EXPECT_EQ(pendulum.jointExternalEffort(i), 0.0);
  EXPECT_THROW(sim.entities().joint("nope"), InputError);
}

TEST(SimulatorProperties, BadJointInputIsRefusedAndChangesNothing) {
  Simulator sim(propertiesWorld(), {});
  sim.properties().setModelConfiguration("pendulum", {"pivot"}, {0.25});
  auto expectThrow = [](const std::function<void()>& f, const std::string& text) {
    try {
      f();
      ADD_FAILURE() << "accepted: " << text;
    } catch (const InputError& e) {
      EXPECT_NE(std::string(e.what()).find(text), std::string::npos) << e.what();
    }
  };
  expectThrow([&] { sim.properties().jointProperties("nope"); }, "joint 'nope' not found");
  expectThrow([&] { sim.properties().jointProperties("ghost::pivot"); }, "no model named 'ghost'");
  JointPropertiesChange c;
  c.damping = kNaN;
  c.lower = -0.1;
  expectThrow([&] { sim.properties().setJointProperties("pivot", c); }, "damping must be finite and >= 0, got nan");
  c = JointPropertiesChange();
  c.damping = -1.0;
  expectThrow([&] { sim.properties().setJointProperties("pivot", c); }, "damping must be finite and >= 0, got -1");
  c = JointPropertiesChange();
  c.lower = 0.5;
  c.upper = 0.1;
  expectThrow([&] { sim.properties().setJointProperties("pivot", c); }, "loStop 0.5 is above hiStop 0.1");
  c = JointPropertiesChange();
  c.velocity = 1.0;
  expectThrow([&] { sim.properties().setJointProperties("pivot", c); }, "vel and fmax go together");
  const JointProperties j = sim.properties().jointProperties("pivot");
  EXPECT_DOUBLE_EQ(j.info.damping, 0.0);
  EXPECT_DOUBLE_EQ(j.info.lower, -1.0);
  EXPECT_DOUBLE_EQ(j.info.upper, 1.0);
  expectThrow([&] { sim.properties().setModelConfiguration("ghost", {"pivot"}, {0.1}); }, "no model named 'ghost'");
  expectThrow([&] { sim.properties().setModelConfiguration("wall", {}, {}); }, "model 'wall' is static");
  expectThrow([&] { sim.properties().setModelConfiguration("pendulum", {"pivot"}, {}); },
              "1 joint names but 0 positions");
  expectThrow([&] { sim.properties().setModelConfiguration("pendulum", {"pivot", "elbow"}, {0.1, 0.2}); },
              "model 'pendulum' has no movable joint 'elbow'");
  expectThrow([&] { sim.properties().setModelConfiguration("pendulum", {"pivot"}, {kNaN}); },
              "joint 'pivot': position nan is not finite");
  EXPECT_DOUBLE_EQ(sim.properties().jointProperties("pivot").position, 0.25);
}

TEST(SimulatorProperties, LinkInertialsAsGazeboReportsThem) {
  Simulator sim(propertiesWorld(), {});
  const LinkProperties l = sim.properties().linkProperties("pendulum::bob");
  EXPECT_DOUBLE_EQ(l.mass, 1.5);
  EXPECT_DOUBLE_EQ(l.com.z(), 0.01);
  EXPECT_DOUBLE_EQ(l.inertia(1, 1), 0.003);
  EXPECT_TRUE(l.gravity_mode);
  EXPECT_THROW(sim.properties().linkProperties("pendulum::arm"), InputError);
  EXPECT_THROW(sim.properties().linkProperties("bob"), InputError);
  EXPECT_THROW(sim.properties().linkProperties("ghost::bob"), InputError);
}

TEST(SimulatorProperties, LightsAreReadSetAndDeleted) {
  Simulator sim(propertiesWorld(), {});
  ASSERT_EQ(sim.properties().lights().size(), 2u);
  const DirectionalLight& sun = sim.properties().lights()[0];
  EXPECT_EQ(sun.name, "sun");
  EXPECT_DOUBLE_EQ(sun.attenuation.constant, 0.9);  // Gazebo's sun/model.sdf
  const DirectionalLight& lamp = sim.properties().lights()[1];
  EXPECT_EQ(lamp.name, "lamp");
  // Drawn dimmed by its attenuation at 2 m: 1 / (0.5 + 0.5 * 2 + 0.25 * 4) = 0.4.
  EXPECT_NEAR(lamp.diffuse[0], 0.4, 1e-6);
  EXPECT_FLOAT_EQ(lamp.given_diffuse[0], 1.0f);
  LightChange c;
  c.diffuse = Eigen::Vector4f(0.2f, 0.4f, 0.6f, 1.0f);
  c.attenuation = {1.0, 0.0, 0.0};
  sim.properties().setLight("lamp", c);
  EXPECT_NEAR(sim.properties().lights()[1].diffuse[1], 0.4, 1e-6);  // no longer dimmed
  EXPECT_THROW(sim.properties().setLight("nope", c), InputError);
  LightChange bad = c;
  bad.diffuse[0] = std::numeric_limits<float>::quiet_NaN();
  EXPECT_THROW(sim.properties().setLight("lamp", bad), InputError);
  bad = c;
  bad.attenuation.linear = -1.0;
  EXPECT_THROW(sim.properties().setLight("lamp", bad), InputError);
  EXPECT_NEAR(sim.properties().lights()[1].diffuse[1], 0.4, 1e-6);  // unchanged
  sim.properties().deleteLight("lamp");
  EXPECT_EQ(sim.properties().lights().size(), 1u);
  EXPECT_THROW(sim.properties().deleteLight("lamp"), InputError);
}

// set_light_properties changes what cameras render: the red box seen by a world model's
// camera (world_model_sensors.world, lit by model://sun) is brighter with the sun turned onto
// its near face, and darker when the sun's diffuse then goes to 0.
TEST(SimulatorProperties, ACameraRendersTheChangedLight) {
  Simulator sim(loadWorldFile(std::string(TEST_DATA_DIR) + "/worlds/world_model_sensors.world"), {});
  const auto* camera =
      dynamic_cast<const SimCamera*>(sim.findSensor(sim.findModel("sensor_post"), "post_camera"));
  ASSERT_NE(camera, nullptr);
  const CameraConfig& c = camera->camera().config();
  const std::size_t middle = (static_cast<std::size_t>(c.height / 2) * c.width + c.width / 2) * 3;
  // The sun shining from behind the camera onto the box's near face (its world direction,
  // -0.5 0.1 -0.9, leaves that face dark), full white.
  LightChange bright;
  bright.diffuse = Eigen::Vector4f(1, 1, 1, 1);
  bright.attenuation = sim.properties().lights()[0].attenuation;
  bright.direction = Eigen::Vector3d(1.0, 0.0, -0.3);
  sim.properties().setLight("sun", bright);
  sim.step(250);
  sim.waitFrames();
  const int lit = camera->camera().image()[middle];
  LightChange dark;
  dark.diffuse = Eigen::Vector4f(0, 0, 0, 1);
  dark.specular = Eigen::Vector4f(0, 0, 0, 1);
  dark.attenuation = sim.properties().lights()[0].attenuation;
  sim.properties().setLight("sun", dark);
  sim.step(250);
  sim.waitFrames();
  const int unlit = camera->camera().image()[middle];
  std::cout << "[set_light_properties] red of the box: " << lit << " in the sun, " << unlit
            << " with the sun's diffuse at 0 (ambient only)\n";
  EXPECT_LT(unlit, lit - 20);
  EXPECT_GT(unlit, 0);  // the ambient light stays
}

}  // namespace
}  // namespace tianracer_sim
