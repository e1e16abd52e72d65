// The one name resolver of the state and property services (simulator/entities.h): models,
// links and joints by Gazebo's names, what moves them, their states, and the errors that the
// ROS services answer with.
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "tianracer_sim/simulator/simulator.h"
#include "tianracer_sim/world/world.h"

#include "sim_test_support.h"

namespace tianracer_sim {
namespace {

using ::testing::HasSubstr;

WorldDescription entitiesWorld() {
  return loadWorldString(
      "<sdf version='1.6'><world name='w'>"
      "<include><uri>model://ground_plane</uri></include>"
      "<model name='pendulum'><pose>0 0 3 0 0 0</pose>"
      "<link name='bob'><pose>0 0 -0.5 0 0 0</pose><inertial><mass>1.5</mass><inertia><ixx>0.002"
      "</ixx><iyy>0.003</iyy><izz>0.004</izz></inertia></inertial><collision name='c'><geometry>"
      "<sphere><radius>0.05</radius></sphere></geometry></collision></link>"
      "<joint name='pivot' type='revolute'><parent>world</parent><child>bob</child>"
      "<axis><xyz>1 0 0</xyz></axis></joint></model>"
      "<model name='wall'><static>true</static><pose>0 5 0.5 0 0 0</pose><link name='link'>"
      "<pose>0 0 0.25 0 0 0</pose><collision name='c'><geometry><box><size>1 0.1 1</size></box>"
      "</geometry></collision></link></model>"
      "</world></sdf>",
      "entities.world", ".");
}

std::string errorOf(const std::function<void()>& f) {
  try {
    f();
  } catch (const InputError& e) {
    return e.what();
  }
  return "";
}

class EntitiesTest : public ::testing::Test {
 protected:
  EntitiesTest() : sim(entitiesWorld(), {}) {
    RobotSpawn car;
    car.name = "tianracer";
    car.model = test::loadTianracer();
    car.X_WB = Eigen::Isometry3d(Eigen::Translation3d(3.0, 0.0, 0.1));
    car_id = sim.addRobot(std::move(car));
  }
  Simulator sim;
  ModelId car_id = kNoModel;
};

TEST_F(EntitiesTest, ModelsAndLinksByGazebosNames) {
  const Entities entities = sim.entities();
  const Entity car = entities.find("tianracer", true);
  EXPECT_EQ(car.id, car_id);
  EXPECT_NE(car.robot, nullptr);
  EXPECT_EQ(car.body, sim.physicsOf(car_id));
  EXPECT_EQ(car.link, "");
  // A robot's link may be any URDF link, one lumped by a fixed joint too.
  EXPECT_EQ(entities.find("tianracer::base_link", false).link, "base_link");
  const Entity pendulum = entities.find("pendulum::bob", false);
  EXPECT_NE(pendulum.model, nullptr);
  EXPECT_NE(pendulum.body, nullptr);  // it moves: its free body
  const Entity wall = entities.find("wall", true);
  EXPECT_EQ(wall.body, nullptr);  // static
  EXPECT_TRUE(entities.find("ground_plane::link", false).ground_plane);
  // States: a static model's link at its pose in the world.
  EXPECT_NEAR(entities.state(entities.find("wall::link", false)).X_WE.translation().z(), 0.75,
              1e-12);
  EXPECT_NEAR(entities.state(car).X_WE.translation().x(), 3.0, 1e-9);
  EXPECT_NEAR(entities.frame("wall").X_WE.translation().y(), 5.0, 1e-12);
  EXPECT_TRUE(entities.frame("world").X_WE.isApprox(Eigen::Isometry3d::Identity()));
  EXPECT_EQ(entities.modelNames(),
            (std::vector<std::string>{"ground_plane", "pendulum", "wall", "tianracer"}));
}

TEST_F(EntitiesTest, WhatIsWrongWithAName) {
  const Entities entities = sim.entities();
  EXPECT_THAT(errorOf([&] { entities.find("nobody", true); }),
              HasSubstr("no model named 'nobody' (models: ground_plane, pendulum, wall, tianracer)"));
  EXPECT_THAT(errorOf([&] { entities.find("tianracer::nope", false); }),
              HasSubstr("model 'tianracer' has no link 'nope'"));
  EXPECT_THAT(errorOf([&] { entities.find("wall", false); }),
              HasSubstr("'wall' is not a link: use gazebo's scoped name \"model::link\""));
  EXPECT_THAT(errorOf([&] { entities.find("::x", false); }), HasSubstr("names no model"));
  EXPECT_THAT(errorOf([&] { entities.find("ground_plane::base", false); }),
              HasSubstr("its one link is 'link'"));
  EXPECT_THAT(errorOf([&] { entities.frame("nowhere"); }),
              HasSubstr("reference_frame: no model named 'nowhere'"));
  // A static model does not move; a state out of bounds changes nothing.
  EXPECT_THAT(errorOf([&] { entities.setBase(entities.find("wall", true), EntityState(), true); }),
              HasSubstr("is static and cannot be moved"));
  EntityState far;
  far.X_WE.translation().x() = 1e12;
  const Entity car = entities.find("tianracer", true);
  EXPECT_NE(errorOf([&] { entities.setBase(car, far, true); }), "");
  EXPECT_NEAR(entities.state(car).X_WE.translation().x(), 3.0, 1e-9);
}

TEST_F(EntitiesTest, JointsByNameThenByModel) {
  const Entities entities = sim.entities();
  const JointRef pivot = entities.joint("pivot");
  EXPECT_EQ(pivot.body, sim.physicsOf(sim.findModel("pendulum")));
  EXPECT_GE(pivot.index, 0);
  const JointRef hinge = entities.joint("tianracer::left_steering_hinge_joint");
  EXPECT_EQ(hinge.body, sim.physicsOf(car_id));
  EXPECT_EQ(entities.joint("left_steering_hinge_joint").body, hinge.body);
  EXPECT_THAT(errorOf([&] { entities.joint("ghost::pivot"); }), HasSubstr("no model named 'ghost'"));
  EXPECT_THAT(errorOf([&] { entities.joint("wall::pivot"); }),
              HasSubstr("no model 'wall' has a movable joint of that name"));
  EXPECT_THAT(errorOf([&] { entities.joint(""); }), HasSubstr("no joint name given"));
}

}  // namespace
}  // namespace tianracer_sim
