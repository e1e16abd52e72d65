// World models as Gazebo simulates them (sim/world_physics.h): links that no joint joins are
// separate bodies, joints inside a model are simulated (revolute, continuous, prismatic, with
// limits, damping, friction and springs), the model frame follows its canonical link, and bad
// joints or mass properties are reported while the rest of the world loads. Each test prints
// its measured figures.
#include <gtest/gtest.h>

#include <cmath>
#include <iostream>
#include <limits>
#include <string>
#include <vector>

#include "tianracer_sim/sim/simulation.h"
#include "tianracer_sim/sim/world_physics.h"
#include "tianracer_sim/world/world.h"

namespace tianracer_sim {
namespace {

constexpr double kG = 9.8;

std::string num(double v) { return std::to_string(v); }

/// <inertial> of a solid box of mass m and size (x, y, z).
std::string boxInertial(double m, double x, double y, double z) {
  return "<inertial><mass>" + num(m) + "</mass><inertia><ixx>" + num(m / 12 * (y * y + z * z)) +
         "</ixx><iyy>" + num(m / 12 * (x * x + z * z)) + "</iyy><izz>" +
         num(m / 12 * (x * x + y * y)) + "</izz></inertia></inertial>";
}

std::string boxCollision(double x, double y, double z) {
  return "<collision name='c'><geometry><box><size>" + num(x) + " " + num(y) + " " + num(z) +
         "</size></box></geometry></collision>";
}

WorldDescription world(const std::string& models, const WarningSink& warn = {}) {
  WorldLoadOptions options;
  options.warn = warn;
  return loadWorldString("<sdf version='1.6'><world name='w'>\n<include><uri>model://ground_plane"
                         "</uri></include>\n" + models + "</world></sdf>",
                         "test.world", ".", options);
}

/// A world loaded into a physics world, with every warning kept.
struct ModelWorld {
  std::vector<std::string> warnings;
  WorldDescription desc;
  PhysicsWorld physics;
  explicit ModelWorld(const std::string& models)
      : desc(world(models, [this](const std::string& w) { warnings.push_back(w); })),
        physics(physicsOptionsFor(desc)) {
    addWorldToPhysics(desc, &physics, [this](const std::string& w) { warnings.push_back(w); });
  }
  PhysicsRobot& model(const std::string& name) {
    const int i = physics.freeBodyIndex(name);
    if (i < 0) throw std::runtime_error("no free body " + name);
    return physics.freeBody(i);
  }
  void run(double seconds) {
    const long n = std::lround(seconds / physics.dt());
    for (long k = 0; k < n; ++k) physics.step();
  }
  std::string allWarnings() const {
    std::string all;
    for (const auto& w : warnings) all += w + "\n";
    return all;
  }
};

/// Two boxes as two links of one model with no joint between them: "low" 1 m up, "high" 2 m up
/// (beside it, or right above it).
std::string twoBoxes(double high_x, const std::string& high_extra = "") {
  return "<model name='pair'><pose>0 0 0 0 0 0.3</pose>"
         "<link name='low'><pose>0 0 1.05 0 0 0</pose>" + boxInertial(1, 0.1, 0.1, 0.1) +
         boxCollision(0.1, 0.1, 0.1) + "</link>"
         "<link name='high'><pose>" + num(high_x) + " 0 2.05 0 0 0</pose>" + high_extra +
         boxInertial(3, 0.1, 0.1, 0.1) + boxCollision(0.1, 0.1, 0.1) + "</link></model>";
}

TEST(WorldModels, LinksWithNoJointFallSeparately) {
  ModelWorld w(twoBoxes(0.5));
  EXPECT_TRUE(w.warnings.empty()) << w.allWarnings();
  PhysicsRobot& pair = w.model("pair");
  ASSERT_EQ(pair.tree().bodies.size(), 2u);
  EXPECT_TRUE(pair.joints().empty());
  // Free fall from 1 m (lowest face 1 m up) takes sqrt(2 h / g); the high box is then still
  // falling, 1 m higher: each link on its own.
  const double t_low = std::sqrt(2.0 * 1.0 / kG);
  w.run(t_low - 0.02);
  const double z_low = pair.linkPose("low").translation().z();
  const double z_high = pair.linkPose("high").translation().z();
  std::cout << "[two links, no joint] after " << t_low - 0.02 << " s: low at z " << z_low
            << ", high at z " << z_high << " (both fell " << 1.05 - z_low << " / " << 2.05 - z_high
            << " m)\n";
  EXPECT_NEAR(1.05 - z_low, 2.05 - z_high, 1e-9);  // the same fall, nothing joins them
  w.run(1.0);
  EXPECT_NEAR(pair.linkPose("low").translation().z(), 0.05, 1e-3);
  EXPECT_NEAR(pair.linkPose("high").translation().z(), 0.05, 1e-3);
  // The model frame follows its canonical (first) link, as in Gazebo.
  EXPECT_TRUE(pair.basePose().isApprox(pair.linkPose("low") *
                                           w.desc.models[0].links[0].X_ML.inverse(),
                                       1e-12));
  // A push on one link moves that link only.
  const Eigen::Vector3d low0 = pair.linkPose("low").translation();
  const Eigen::Vector3d high0 = pair.linkPose("high").translation();
  pair.setExternalWrench("high", Eigen::Vector3d(60.0, 0.0, 0.0), Eigen::Vector3d::Zero());
  w.run(0.5);
  pair.setExternalWrench("high", Eigen::Vector3d::Zero(), Eigen::Vector3d::Zero());
  w.run(0.5);
  const double moved_high = (pair.linkPose("high").translation() - high0).norm();
  const double moved_low = (pair.linkPose("low").translation() - low0).norm();
  std::cout << "[two links, no joint] pushed 'high' for 0.5 s: it moved " << moved_high
            << " m, 'low' " << moved_low << " m\n";
  EXPECT_GT(moved_high, 0.1);
  EXPECT_LT(moved_low, 1e-4);
}

// Gazebo: the links of one model collide with each other only when one of them sets
// <self_collide> (SDF's default is false).
TEST(WorldModels, LinksOfOneModelCollideOnlyWithSelfCollide) {
  ModelWorld through(twoBoxes(0.0));
  through.run(2.0);
  const double z_through = through.model("pair").linkPose("high").translation().z();
  ModelWorld stacked(twoBoxes(0.0, "<self_collide>true</self_collide>"));
  stacked.run(2.0);
  const double z_stacked = stacked.model("pair").linkPose("high").translation().z();
  std::cout << "[box above box, one model] the high box rests at z " << z_through
            << " (no self_collide: through the low one), " << z_stacked
            << " (self_collide: on it)\n";
  EXPECT_NEAR(z_through, 0.05, 1e-3);
  EXPECT_NEAR(z_stacked, 0.15, 2e-3);
}

/// A pendulum: a bob of mass m (inertia i about its centre) on a massless rod of length L,
/// hinged to the world about x. Its joint frame sits L above the bob (the joint's <pose> in
/// the bob's frame).
std::string pendulum(double m, double i, double L, const std::string& axis_extra = "") {
  return "<model name='pendulum'><pose>1 2 3 0 0 0</pose>"
         "<link name='bob'><pose>0 0 " + num(-L) + " 0 0 0</pose><inertial><mass>" + num(m) +
         "</mass><inertia><ixx>" + num(i) + "</ixx><iyy>" + num(i) + "</iyy><izz>" + num(i) +
         "</izz></inertia></inertial><collision name='c'><geometry><sphere><radius>0.05</radius>"
         "</sphere></geometry></collision></link>"
         "<joint name='pivot' type='revolute'><parent>world</parent><child>bob</child>"
         "<pose>0 0 " + num(L) + " 0 0 0</pose><axis><xyz>1 0 0</xyz>" + axis_extra +
         "</axis></joint></model>";
}

TEST(WorldModels, PendulumSwingsWithTheSmallAnglePeriod) {
  const double m = 1.5, i = 2e-3, L = 0.8, theta0 = 0.05;
  ModelWorld w(pendulum(m, i, L));
  EXPECT_TRUE(w.warnings.empty()) << w.allWarnings();
  PhysicsRobot& p = w.model("pendulum");
  ASSERT_EQ(p.joints().size(), 1u);
  const JointInfo& joint = p.joints()[0];
  EXPECT_EQ(joint.name, "pivot");
  EXPECT_EQ(joint.parent_link, "world");
  EXPECT_EQ(joint.child_link, "bob");
  EXPECT_EQ(joint.type, JointType::kRevolute);
  EXPECT_FALSE(joint.has_position_limits);  // SDF's default limits are +-1e16: none
  p.setJointState(0, theta0, 0.0);
  // The bob hangs from the pivot (1 2 3) at angle theta0 about x.
  const Eigen::Vector3d bob = p.linkPose("bob").translation();
  EXPECT_NEAR(bob.y(), 2.0 + L * std::sin(theta0), 1e-12);
  EXPECT_NEAR(bob.z(), 3.0 - L * std::cos(theta0), 1e-12);
  // Upward zero crossings of the angle, interpolated, over 6 periods.
  std::vector<double> crossings;
  double prev = p.jointPosition(0);
  while (crossings.size() < 7 && w.physics.time() < 30.0) {
    w.physics.step();
    const double q = p.jointPosition(0);
    if (prev < 0.0 && q >= 0.0) {
      crossings.push_back(w.physics.time() - w.physics.dt() * q / (q - prev));
    }
    prev = q;
  }
  ASSERT_EQ(crossings.size(), 7u);
  const double period = (crossings.back() - crossings.front()) / 6.0;
  // Compound pendulum, small angles: T = 2 pi sqrt((i + m L^2) / (m g L)); at amplitude
  // theta0 the true period is longer by theta0^2 / 16 (0.016 %).
  const double analytic = 2.0 * M_PI * std::sqrt((i + m * L * L) / (m * kG * L));
  std::cout << "[pendulum L " << L << " m, amplitude " << theta0 << " rad] period " << period
            << " s, analytic " << analytic << " s (" << 100.0 * (period / analytic - 1.0)
            << " %)\n";
  EXPECT_NEAR(period, analytic, 2e-3 * analytic);
  // No joint friction or damping: the amplitude stays.
  double amplitude = 0.0;
  for (int k = 0; k < 2100; ++k) {
    w.physics.step();
    amplitude = std::max(amplitude, std::abs(p.jointPosition(0)));
  }
  std::cout << "[pendulum] amplitude after " << w.physics.time() << " s: " << amplitude << " rad\n";
  EXPECT_NEAR(amplitude, theta0, 1e-3 * theta0);
  // The model frame follows the bob (the canonical link) as it swings.
  EXPECT_TRUE(p.basePose().isApprox(p.linkPose("bob") * w.desc.models[0].links[0].X_ML.inverse(),
                                    1e-12));
  // reset_world: back to the file's pose, joint at 0 and at rest.
  p.resetToSpawn();
  EXPECT_EQ(p.jointPosition(0), 0.0);
  EXPECT_EQ(p.jointVelocity(0), 0.0);
  EXPECT_TRUE(p.linkPose("bob").isApprox(w.desc.models[0].X_WM * w.desc.models[0].links[0].X_ML, 1e-12));
}

/// A disc spinning about a vertical axis hinged to the world (gravity does no work on it).
std::string turntable(const std::string& dynamics) {
  return "<model name='turntable'><pose>0 0 1 0 0 0</pose><link name='disc'><inertial><mass>2"
         "</mass><inertia><ixx>0.3</ixx><iyy>0.3</iyy><izz>0.5</izz></inertia></inertial>"
         "<collision name='c'><geometry><cylinder><radius>0.5</radius><length>0.05</length>"
         "</cylinder></geometry></collision></link>"
         "<joint name='spin' type='continuous'><parent>world</parent><child>disc</child>"
         "<axis><xyz>0 0 1</xyz><dynamics>" + dynamics + "</dynamics></axis></joint></model>";
}

// What get/set_joint_properties need from the core: names, positions and rates per world
// model, and damping, friction, limits and a velocity with a force cap to set.
TEST(WorldModels, JointPropertiesCanBeReadAndSet) {
  ModelWorld w(pendulum(1.0, 1e-3, 0.5));
  PhysicsRobot& p = w.model("pendulum");
  const int pivot = p.jointIndex("pivot");
  ASSERT_EQ(pivot, 0);
  EXPECT_EQ(p.jointIndex("nothing"), -1);
  p.setJointState(pivot, 0.3, 0.0);
  w.run(0.2);
  EXPECT_LT(p.jointPosition(pivot), 0.3);
  EXPECT_LT(p.jointVelocity(pivot), 0.0);
  // Limits (hiStop/loStop), set mid-swing outside them: the joint is brought back within
  // 0.5 s and then swings within +-0.1 rad.
  const double q_set = p.jointPosition(pivot);
  p.setJointLimits(pivot, -0.1, 0.1);
  EXPECT_TRUE(p.joints()[pivot].has_position_limits);
  w.run(0.5);
  double qmin = 0.0, qmax = 0.0;
  for (int k = 0; k < 2000; ++k) {
    w.physics.step();
    qmin = std::min(qmin, p.jointPosition(pivot));
    qmax = std::max(qmax, p.jointPosition(pivot));
  }
  std::cout << "[set_joint_properties] limits +-0.1 rad set at " << q_set << " rad: from 0.5 s on "
            << qmin << " .. " << qmax << "\n";
  EXPECT_GT(qmin, -0.1 - 1e-3);
  EXPECT_LT(qmax, 0.1 + 1e-3);
  // Damping: the swing dies out.
  p.setJointDamping(pivot, 2.0);
  EXPECT_EQ(p.joints()[pivot].damping, 2.0);
  w.run(5.0);
  EXPECT_LT(std::abs(p.jointVelocity(pivot)), 1e-3);
  // A velocity with a force cap (vel, fmax): it turns at 0.2 rad/s, up to the limit.
  p.setJointLimits(pivot, -1.0, 1.0);
  p.setJointVelocityTarget(pivot, 0.2, 20.0);
  w.run(1.0);
  EXPECT_NEAR(p.jointVelocity(pivot), 0.2, 1e-3);
  EXPECT_NEAR(p.jointEffort(pivot), 9.8 * 1.0 * 0.5 * std::sin(p.jointPosition(pivot)) + 2.0 * 0.2, 0.05);
  p.clearJointCommand(pivot);
  p.setJointFriction(pivot, 100.0);  // holds it against gravity
  w.run(0.5);
  const double held = p.jointPosition(pivot);
  w.run(1.0);
  EXPECT_NEAR(p.jointPosition(pivot), held, 1e-3);
  // Bad values change nothing.
  EXPECT_THROW(p.setJointDamping(pivot, -1.0), PhysicsError);
  EXPECT_THROW(p.setJointFriction(pivot, std::nan("")), PhysicsError);
  EXPECT_THROW(p.setJointLimits(pivot, 1.0, -1.0), PhysicsError);
  try {
    p.setJointLimits(pivot, 0.0, std::numeric_limits<double>::infinity());
    ADD_FAILURE();
  } catch (const PhysicsError& e) {
    EXPECT_STREQ(e.what(), "model 'pendulum' joint 'pivot': limits must be finite with lower <= upper, "
                           "got 0.000000 .. inf");
  }
  EXPECT_EQ(p.joints()[pivot].damping, 2.0);
  EXPECT_EQ(p.joints()[pivot].lower, -1.0);
  ModelWorld t(turntable(""));
  EXPECT_THROW(t.model("turntable").setJointLimits(0, -1, 1), PhysicsError);  // continuous
}

TEST(WorldModels, PrismaticJointStaysWithinItsLimits) {
  // A 2 kg carriage on a vertical rail, limits -0.2 .. 0.1 m: gravity takes it to the lower
  // limit, then 60 N upwards to the upper one.
  const std::string model =
      "<model name='lift'><pose>0 0 1 0 0 0</pose><link name='carriage'>" +
      boxInertial(2, 0.2, 0.2, 0.1) + boxCollision(0.2, 0.2, 0.1) +
      "</link><joint name='rail' type='prismatic'><parent>world</parent><child>carriage</child>"
      "<axis><xyz>0 0 1</xyz><limit><lower>-0.2</lower><upper>0.1</upper><effort>50</effort>"
      "<velocity>2</velocity></limit></axis></joint></model>";
  ModelWorld w(model);
  EXPECT_TRUE(w.warnings.empty()) << w.allWarnings();
  PhysicsRobot& lift = w.model("lift");
  ASSERT_EQ(lift.joints().size(), 1u);
  const JointInfo& j = lift.joints()[0];
  EXPECT_EQ(j.type, JointType::kPrismatic);
  EXPECT_TRUE(j.has_position_limits);
  EXPECT_EQ(j.lower, -0.2);
  EXPECT_EQ(j.upper, 0.1);
  EXPECT_EQ(j.effort_limit, 50.0);
  EXPECT_EQ(j.velocity_limit, 2.0);
  double qmin = 0.0, qmax = 0.0;
  auto run = [&](double seconds) {
    for (long k = 0; k < std::lround(seconds / w.physics.dt()); ++k) {
      w.physics.step();
      qmin = std::min(qmin, lift.jointPosition(0));
      qmax = std::max(qmax, lift.jointPosition(0));
    }
  };
  run(1.0);
  const double q_low = lift.jointPosition(0);
  lift.setExternalWrench("carriage", Eigen::Vector3d(0, 0, 60.0), Eigen::Vector3d::Zero());
  run(1.0);
  const double q_high = lift.jointPosition(0);
  std::cout << "[prismatic, limits -0.2 .. 0.1 m] rests at " << q_low << " (gravity), "
            << q_high << " (pushed up); over the run " << qmin << " .. " << qmax << " m\n";
  EXPECT_NEAR(q_low, -0.2, 1e-3);
  EXPECT_NEAR(q_high, 0.1, 1e-3);
  EXPECT_GT(qmin, -0.2 - 2e-3);
  EXPECT_LT(qmax, 0.1 + 2e-3);
  // The carriage's world pose follows the joint: the rail is vertical through the model origin.
  EXPECT_NEAR(lift.linkPose("carriage").translation().z(), 1.0 + q_high, 1e-9);
}

TEST(WorldModels, SpringWhoseReferenceLiesBeyondTheLimitHoldsTheJointThereUnderASmallerLoad) {
  // cart_soft_suspension's suspension (osrf/gazebo_models): limits +-0.0375 m, 2500 N/m towards
  // 0.05 m, damping 100. The spring pushes 2500 (0.05 - 0.0375) = 31.25 N at the limit: a
  // 2.5 kg load (24.5 N, the cart's chassis share) stays at the limit, a 4 kg one (39.2 N)
  // rests inside it where the spring carries it, q = 0.05 - 39.2 / 2500. Gazebo's ODE reaches
  // the same rest (ODEJoint::ApplyImplicitStiffnessDamping: the spring, then the hard limit).
  const auto rail = [](const std::string& name, double x, double mass) {
    return "<model name='" + name + "'><pose>" + num(x) + " 0 1 0 0 0</pose><link name='load'>" +
           boxInertial(mass, 0.1, 0.1, 0.1) + boxCollision(0.1, 0.1, 0.1) +
           "</link><joint name='susp' type='prismatic'><parent>world</parent><child>load</child>"
           "<axis><xyz>0 0 1</xyz><limit><lower>-0.0375</lower><upper>0.0375</upper></limit>"
           "<dynamics><damping>100</damping><spring_stiffness>2500</spring_stiffness>"
           "<spring_reference>0.05</spring_reference></dynamics></axis><physics><ode>"
           "<implicit_spring_damper>1</implicit_spring_damper></ode></physics></joint></model>";
  };
  ModelWorld w(rail("light", 0, 2.5) + rail("heavy", 1, 4.0));
  PhysicsRobot& light = w.model("light");
  PhysicsRobot& heavy = w.model("heavy");
  w.run(3.0);
  std::cout << "[spring beyond the limit] 2.5 kg at " << light.jointPosition(0) << " m, 4 kg at "
            << heavy.jointPosition(0) << " m\n";
  EXPECT_NEAR(light.jointPosition(0), 0.0375, 2e-4);
  EXPECT_NEAR(heavy.jointPosition(0), 0.05 - 4.0 * kG / 2500, 5e-4);
  w.run(10.0);  // and they stay
  EXPECT_NEAR(light.jointPosition(0), 0.0375, 2e-4);
  EXPECT_NEAR(heavy.jointPosition(0), 0.05 - 4.0 * kG / 2500, 5e-4);
}

TEST(WorldModels, JointDampingDecaysExponentially) {
  // I w' = -c w: w(t) = w0 exp(-c t / I).
  const double I = 0.5, c = 0.2, w0 = 3.0;
  ModelWorld w(turntable("<damping>" + num(c) + "</damping>"));
  PhysicsRobot& t = w.model("turntable");
  EXPECT_EQ(t.joints()[0].type, JointType::kContinuous);
  EXPECT_EQ(t.joints()[0].damping, c);
  t.setJointState(0, 0.0, w0);
  for (const double at : {1.0, 2.0, 4.0}) {
    w.run(at - w.physics.time());
    const double expected = w0 * std::exp(-c * at / I);
    std::cout << "[damping " << c << " N m s] rate after " << at << " s: " << t.jointVelocity(0)
              << " rad/s, w0 exp(-c t / I) = " << expected << "\n";
    EXPECT_NEAR(t.jointVelocity(0), expected, 5e-3 * expected);
  }
}

TEST(WorldModels, JointFrictionStopsTheJointAtAConstantRate) {
  // I w' = -f sign(w) until it stops: w(t) = w0 - f t / I, at rest from w0 I / f on.
  const double I = 0.5, f = 0.1, w0 = 1.0;
  ModelWorld w(turntable("<friction>" + num(f) + "</friction>"));
  PhysicsRobot& t = w.model("turntable");
  t.setJointState(0, 0.0, w0);
  w.run(2.0);
  const double at2 = t.jointVelocity(0);
  w.run(4.0);
  std::cout << "[friction " << f << " N m] rate after 2 s: " << at2 << " rad/s (expected "
            << w0 - f * 2.0 / I << "), after 6 s: " << t.jointVelocity(0) << " (stopped at "
            << w0 * I / f << " s)\n";
  EXPECT_NEAR(at2, w0 - f * 2.0 / I, 0.01 * (w0 - f * 2.0 / I));
  EXPECT_LT(std::abs(t.jointVelocity(0)), 1e-6);
}

TEST(WorldModels, JointSpringOscillatesAtItsNaturalFrequency) {
  // I q'' = -k (q - q_ref): period 2 pi sqrt(I / k) about q_ref.
  const double I = 0.5, k = 2.0, q_ref = 0.3;
  ModelWorld w(turntable("<spring_reference>" + num(q_ref) + "</spring_reference>"
                         "<spring_stiffness>" + num(k) + "</spring_stiffness>"));
  PhysicsRobot& t = w.model("turntable");
  std::vector<double> crossings;
  double prev = t.jointPosition(0) - q_ref;
  while (crossings.size() < 4 && w.physics.time() < 20.0) {
    w.physics.step();
    const double e = t.jointPosition(0) - q_ref;
    if (prev < 0.0 && e >= 0.0) crossings.push_back(w.physics.time() - w.physics.dt() * e / (e - prev));
    prev = e;
  }
  ASSERT_EQ(crossings.size(), 4u);
  const double period = (crossings.back() - crossings.front()) / 3.0;
  const double analytic = 2.0 * M_PI * std::sqrt(I / k);
  std::cout << "[spring " << k << " N m/rad] period " << period << " s, 2 pi sqrt(I/k) = "
            << analytic << " s\n";
  EXPECT_NEAR(period, analytic, 2e-3 * analytic);
}

// A door on a hinge with limits and a leaf with a handle (a fixed joint), hinged to a frame
// that stands on the ground as a free link: the frame is a floating base, the leaf its link.
TEST(WorldModels, DoorOnAFreeFrameOpensWithinItsLimits) {
  const std::string model =
      "<model name='door'><pose>0 0 0 0 0 0</pose>"
      "<link name='frame'><pose>0 0 0.5 0 0 0</pose>" + boxInertial(40, 0.6, 0.6, 1.0) +
      boxCollision(0.6, 0.6, 1.0) + "</link>"
      "<link name='leaf'><pose>0.55 0.3 0.5 0 0 0</pose>" + boxInertial(5, 0.5, 0.02, 0.9) +
      boxCollision(0.5, 0.02, 0.9) + "</link>"
      "<link name='handle'><pose>0.75 0.33 0.5 0 0 0</pose>" + boxInertial(0.2, 0.02, 0.04, 0.1) +
      "</link>"
      "<joint name='hinge' type='revolute'><parent>frame</parent><child>leaf</child>"
      "<pose>-0.25 0 0 0 0 0</pose><axis><xyz>0 0 1</xyz><limit><lower>0</lower><upper>1.2"
      "</upper></limit><dynamics><damping>1</damping></dynamics></axis></joint>"
      "<joint name='grip' type='fixed'><parent>leaf</parent><child>handle</child></joint></model>";
  ModelWorld w(model);
  EXPECT_TRUE(w.warnings.empty()) << w.allWarnings();
  PhysicsRobot& door = w.model("door");
  ASSERT_EQ(door.tree().bodies.size(), 2u);  // frame; leaf + handle
  EXPECT_EQ(door.tree().links.at("handle").first, 1);
  ASSERT_EQ(door.joints().size(), 1u);
  EXPECT_EQ(door.joints()[0].parent_link, "frame");
  w.run(0.5);
  // A torque about the hinge opens the leaf (against its damping) until the limit at 1.2.
  double qmax = 0.0;
  door.setExternalWrench("leaf", Eigen::Vector3d::Zero(), Eigen::Vector3d(0, 0, 4.0));  // N m
  for (int k = 0; k < 3000; ++k) {
    w.physics.step();
    qmax = std::max(qmax, door.jointPosition(0));
  }
  const Eigen::Vector3d frame = door.linkPose("frame").translation();
  std::cout << "[door, hinge limits 0 .. 1.2 rad] opened to " << door.jointPosition(0)
            << " rad (max " << qmax << "); its frame stands at " << frame.transpose() << "\n";
  EXPECT_NEAR(door.jointPosition(0), 1.2, 2e-3);
  EXPECT_LT(qmax, 1.2 + 5e-3);
  EXPECT_NEAR(frame.z(), 0.5, 2e-3);  // the frame stays on the ground
  // The handle moves with the leaf (fixed joint).
  const Eigen::Isometry3d X_LH = door.linkPose("leaf").inverse() * door.linkPose("handle");
  EXPECT_TRUE(X_LH.translation().isApprox(Eigen::Vector3d(0.2, 0.03, 0.0), 1e-9));
}

TEST(WorldModels, JointAxisInTheModelFrame) {
  // The bob's link is turned 90 deg about z, so the model's x is the link's -y: the pendulum
  // must still swing in the model's y-z plane.
  for (const std::string& axis : {std::string("<xyz expressed_in='__model__'>1 0 0</xyz>"),
                                  std::string("<xyz>1 0 0</xyz><use_parent_model_frame>true"
                                              "</use_parent_model_frame>")}) {
    const std::string model =
        "<model name='p'><pose>0 0 3 0 0 0</pose><link name='bob'><pose>0 0 -1 0 0 1.5707963267948966"
        "</pose>" + boxInertial(1, 0.1, 0.1, 0.1) + "</link><joint name='pivot' type='revolute'>"
        "<parent>world</parent><child>bob</child><pose>0 0 1 0 0 0</pose><axis>" + axis +
        "</axis></joint></model>";
    ModelWorld w(model);
    PhysicsRobot& p = w.model("p");
    p.setJointState(0, 0.1, 0.0);
    const Eigen::Vector3d bob = p.linkPose("bob").translation();
    std::cout << "[axis in the model frame: " << axis << "] bob at " << bob.transpose() << "\n";
    EXPECT_NEAR(bob.x(), 0.0, 1e-12);
    EXPECT_NEAR(std::abs(bob.y()), std::sin(0.1), 1e-12);
  }
}

TEST(WorldModels, SceneAndLinkStatesFollowEachLink) {
  const WorldDescription desc = world(twoBoxes(0.5));
  PhysicsWorld physics(physicsOptionsFor(desc));
  addWorldToPhysics(desc, &physics, {});
  Scene scene;
  const auto bodies = addToScene(desc, scene);
  PhysicsRobot& pair = physics.freeBody(physics.freeBodyIndex("pair"));
  pair.setExternalWrench("high", Eigen::Vector3d(20, 0, 0), Eigen::Vector3d::Zero());
  for (int k = 0; k < 800; ++k) physics.step();
  updateFreeBodyScene(physics, &scene);
  for (const std::string link : {"low", "high"}) {
    EXPECT_TRUE(scene.bodies[bodies.at("pair::" + link)].X_WB.isApprox(pair.linkPose(link), 1e-12));
  }
  EXPECT_GT(pair.linkTwist("high").linear.x(), 1.0);
  EXPECT_NEAR(pair.linkTwist("low").linear.x(), 0.0, 1e-6);
}

TEST(WorldModels, SetModelStateMovesEveryLinkWithTheModelFrame) {
  ModelWorld w(twoBoxes(0.5));
  PhysicsRobot& pair = w.model("pair");
  w.run(1.5);  // both at rest on the ground, apart
  const Eigen::Isometry3d X_ML = pair.basePose().inverse() * pair.linkPose("high");
  Eigen::Isometry3d X = Eigen::Isometry3d::Identity();
  X.translation() = Eigen::Vector3d(3, -1, 0.5);
  X.linear() = Eigen::AngleAxisd(1.0, Eigen::Vector3d::UnitZ()).toRotationMatrix();
  pair.setBasePose(X);
  EXPECT_TRUE(pair.basePose().isApprox(X, 1e-12));
  EXPECT_TRUE((pair.basePose().inverse() * pair.linkPose("high")).isApprox(X_ML, 1e-12));
  Twist v;
  v.linear = Eigen::Vector3d(1, 0, 0);
  pair.setBaseTwist(v);
  EXPECT_TRUE(pair.linkTwist("high").linear.isApprox(v.linear, 1e-12));
  EXPECT_TRUE(pair.baseTwist().linear.isApprox(v.linear, 1e-12));
}

TEST(WorldModels, ModelWeldedToTheWorldStaysStatic) {
  ModelWorld w("<model name='post'><pose>1 0 0.5 0 0 0</pose><link name='l'>" +
               boxInertial(1, 0.1, 0.1, 1) + boxCollision(0.1, 0.1, 1) +
               "</link><joint name='j' type='fixed'><parent>world</parent><child>l</child></joint>"
               "</model>");
  EXPECT_EQ(w.physics.freeBodyIndex("post"), -1);
  EXPECT_TRUE(isHeldStatic(w.desc.models[0]));
  EXPECT_TRUE(w.warnings.empty()) << w.allWarnings();
}

// A static model's collision (and an actor's, which Simulator then moves): named
// model::link::collision, at X_WM X_ML X_LS, with the collision's surface and shape.
TEST(WorldModels, StaticShapeOfACollisionIsAtTheModelPose) {
  const WorldDescription desc = world(
      "<model name='wall'><static>true</static><pose>1 2 0 0 0 1.5707963267948966</pose>"
      "<link name='l'><pose>0.5 0 0 0 0 0</pose><collision name='c'><pose>0 0 0.25 0 0 0</pose>"
      "<geometry><box><size>0.1 0.2 0.5</size></box></geometry><surface><friction><ode>"
      "<mu>0.3</mu><mu2>0.4</mu2></ode></friction></surface></collision></link></model>");
  const ModelDescription& m = desc.models.back();
  ASSERT_EQ(m.name, "wall");
  const StaticShape s = staticShapeOf(m, m.links[0], m.links[0].collisions[0]);
  EXPECT_EQ(s.name, "wall::l::c");
  EXPECT_TRUE(s.X_WS.translation().isApprox(Eigen::Vector3d(1.0, 2.5, 0.25), 1e-12))
      << s.X_WS.translation().transpose();
  EXPECT_TRUE(s.X_WS.isApprox(m.X_WM * m.links[0].X_ML * m.links[0].collisions[0].X_LS));
  EXPECT_EQ(s.shape.type, ShapeType::kBox);
  EXPECT_EQ(s.shape.size, Eigen::Vector3d(0.1, 0.2, 0.5));
  EXPECT_EQ(s.surface.mu1, 0.3);
  EXPECT_EQ(s.surface.mu2, 0.4);
}

TEST(WorldModels, JointNamingAMissingLinkIsLeftOutAndTheWorldLoads) {
  ModelWorld w(twoBoxes(0.5).substr(0, twoBoxes(0.5).size() - 8) +
               "<joint name='glue' type='fixed'>\n<parent>low</parent><child>nowhere</child>"
               "</joint></model>\n" +
               "<model name='crate'><pose>2 0 0.5 0 0 0</pose><link name='link'>" +
               boxInertial(1, 0.2, 0.2, 0.2) + boxCollision(0.2, 0.2, 0.2) + "</link></model>");
  ASSERT_EQ(w.warnings.size(), 1u) << w.allWarnings();
  std::cout << "[bad joint] " << w.warnings[0] << "\n";
  EXPECT_NE(w.warnings[0].find("test.world:3: model 'pair' joint 'glue': no link 'nowhere' in the "
                               "model (links: low, high); the joint is left out"),
            std::string::npos);
  EXPECT_TRUE(w.desc.models[0].joints.empty());
  EXPECT_EQ(w.model("pair").tree().bodies.size(), 2u);
  w.run(1.0);
  EXPECT_NEAR(w.model("crate").basePose().translation().z(), 0.1, 1e-3);
}

// A two-wheeled base on a frictionless castor, written as Gazebo's library writes one (create,
// pioneer2dx): wheel cylinders turned by "0 1.5707 1.5707" (96 urad short of pi/2) on revolute
// joints without <limit>. It must stand still. With the cylinders as plain Bullet cylinders
// lying on the plane it rolled off, faster and faster (the library's create: 5.2 cm in 30 s).
TEST(WorldModels, TwoWheeledBaseOnAFrictionlessCastorStandsStill) {
  std::string wheels;
  for (const char* side : {"left", "right"}) {
    const std::string y = std::string(side) == "left" ? "0.13" : "-0.13";
    wheels += std::string("<link name='") + side + "_wheel'><pose>0 " + y +
              " 0.033 0 0 0</pose><inertial><mass>0.1</mass><inertia><ixx>0.001</ixx><iyy>0.001"
              "</iyy><izz>0.001</izz></inertia></inertial><collision name='c'><pose>0 0 0 0 "
              "1.5707 1.5707</pose><geometry><cylinder><radius>0.033</radius><length>0.023"
              "</length></cylinder></geometry><surface><friction><ode><mu>10</mu><mu2>10</mu2>"
              "</ode></friction></surface></collision></link><joint name='" + side +
              "' type='revolute'><parent>base</parent><child>" + side + "_wheel</child><axis>"
              "<xyz>0 1 0</xyz></axis></joint>";
  }
  ModelWorld w("<model name='bot'><link name='base'><inertial><pose>0.002 0 0.03 0 0 0</pose>"
               "<mass>2.2</mass><inertia><ixx>0.02</ixx><iyy>0.02</iyy><izz>0.03</izz></inertia>"
               "</inertial><collision name='castor'><pose>0.13 0 0.018 0 0 0</pose><geometry>"
               "<sphere><radius>0.018</radius></sphere></geometry><surface><friction><ode><mu>0"
               "</mu><mu2>0</mu2></ode></friction></surface></collision></link>" +
               wheels + "</model>");
  EXPECT_TRUE(w.warnings.empty()) << w.allWarnings();
  PhysicsRobot& bot = w.model("bot");
  w.run(1.0);
  const Eigen::Vector3d start = bot.basePose().translation();
  w.run(20.0);
  const double moved = (bot.basePose().translation() - start).norm();
  std::cout << "[two-wheeled base] moved " << moved * 1000 << " mm in 20 s\n";
  EXPECT_LT(moved, 1e-3);
}

TEST(WorldModels, BadMassOrInertiaOfAMovingLinkIsReportedAndTheModelHeldStatic) {
  const std::string crate = "<model name='crate'><pose>2 0 0.5 0 0 0</pose><link name='link'>" +
                            boxInertial(1, 0.2, 0.2, 0.2) + boxCollision(0.2, 0.2, 0.2) +
                            "</link></model>\n";
  struct Case {
    std::string inertial, message;
  };
  const Case cases[] = {
      {"<inertial><mass>0</mass></inertial>",
       "test.world:5: model 'm' link 'l': <mass> must be > 0 (got 0) for a link that moves; the "
       "model is held static"},
      {"<inertial><mass>-2</mass></inertial>", "<mass> must be > 0 (got -2)"},
      {"<inertial><mass>1</mass><inertia><ixx>-0.1</ixx><iyy>1</iyy><izz>1</izz></inertia>"
       "</inertial>",
       "test.world:5: model 'm' link 'l': inertia (ixx iyy izz ixy ixz iyz) = (-0.1 1 1 0 0 0) is "
       "not positive definite"},
      {"<inertial><mass>1</mass><inertia><ixx>0</ixx><iyy>0</iyy><izz>0</izz></inertia>"
       "</inertial>",
       "is not positive definite"},
      // sdformat reads "nan" as a number: it gets here, and is refused here.
      {"<inertial><mass>1</mass><inertia><ixx>nan</ixx><iyy>1</iyy><izz>1</izz></inertia>"
       "</inertial>",
       "inertia (ixx iyy izz ixy ixz iyz) = (nan 1 1 0 0 0) is not positive definite"},
      {"<inertial><mass>nan</mass></inertial>", "<mass> must be > 0 (got nan)"},
  };
  for (const Case& c : cases) {
    ModelWorld w("<model name='m'><pose>0 0 1 0 0 0</pose>\n<link name='l'>\n" + c.inertial +
                 boxCollision(0.2, 0.2, 0.2) + "</link></model>\n" + crate);
    ASSERT_EQ(w.warnings.size(), 1u) << w.allWarnings();
    std::cout << "[bad mass properties] " << w.warnings[0] << "\n";
    EXPECT_NE(w.warnings[0].find(c.message), std::string::npos) << w.warnings[0];
    EXPECT_EQ(w.physics.freeBodyIndex("m"), -1);  // held static where the file puts it
    w.run(1.0);
    EXPECT_NEAR(w.model("crate").basePose().translation().z(), 0.1, 1e-3);  // the rest moves
  }
  // Moments that violate the triangle inequality (no rigid body has them; Gazebo's create base
  // does): warned, simulated as given, as Gazebo (ODE's dMassCheck asks positive definite only).
  {
    ModelWorld w("<model name='m'><pose>0 0 1 0 0 0</pose>\n<link name='l'>\n<inertial><mass>1"
                 "</mass><inertia><ixx>1</ixx><iyy>1</iyy><izz>5</izz></inertia></inertial>" +
                 boxCollision(0.2, 0.2, 0.2) + "</link></model>\n" + crate);
    ASSERT_EQ(w.warnings.size(), 1u) << w.allWarnings();
    EXPECT_NE(w.warnings[0].find("test.world:3: model 'm' link 'l': the principal moments of "
                                 "inertia of the links moving with it, (1 1 5), violate the "
                                 "triangle inequality (each at most the sum of the other two); "
                                 "simulated as given, as Gazebo does"),
              std::string::npos)
        << w.warnings[0];
    ASSERT_NE(w.physics.freeBodyIndex("m"), -1);
    w.run(3.0);
    EXPECT_NEAR(w.model("m").basePose().translation().z(), 0.1, 1e-2);  // fell onto the ground
    EXPECT_TRUE(w.model("m").basePose().matrix().allFinite());
  }
  // A static model, and a link welded to the world, may carry any mass: they never move.
  // Gazebo's saved worlds write nan in a static link's inertia (TurtleBot3's autorace world).
  for (const std::string& m :
       {std::string("<model name='m'><static>true</static><link name='l'><inertial><mass>0</mass>"
                    "</inertial></link></model>"),
        std::string("<model name='m'><static>1</static><link name='l'><inertial><inertia>"
                    "<ixx>nan</ixx><ixy>0</ixy><ixz>0</ixz><iyy>nan</iyy><iyz>0</iyz><izz>nan"
                    "</izz></inertia><mass>0</mass></inertial>" + boxCollision(0.2, 0.2, 0.2) +
                    "</link></model>"),
        std::string("<model name='m'><link name='base'><inertial><mass>0</mass></inertial></link>"
                    "<link name='arm'><pose>0 0 1 0 0 0</pose>" + boxInertial(1, 0.1, 0.1, 0.5) +
                    boxCollision(0.1, 0.1, 0.5) + "</link>"
                    "<joint name='w' type='fixed'><parent>world</parent><child>base</child></joint>"
                    "<joint name='j' type='revolute'><parent>base</parent><child>arm</child>"
                    "<axis><xyz>0 1 0</xyz></axis></joint></model>")}) {
    ModelWorld w(m);
    EXPECT_TRUE(w.warnings.empty()) << w.allWarnings();
  }
}

TEST(WorldModels, UnsupportedJointsAndLoopsAreWarned) {
  const std::string links =
      "<link name='a'>" + boxInertial(1, 0.1, 0.1, 0.1) + boxCollision(0.1, 0.1, 0.1) +
      "</link><link name='b'>" +
      boxInertial(1, 0.1, 0.1, 0.1) + "</link><link name='c'>" + boxInertial(1, 0.1, 0.1, 0.1) +
      "</link>";
  ModelWorld w("<model name='m'><pose>0 0 2 0 0 0</pose>" + links +
               "<joint name='ball' type='ball'><parent>a</parent><child>b</child></joint>"
               "<joint name='j1' type='revolute'><parent>b</parent><child>c</child></joint>"
               "<joint name='j2' type='revolute'><parent>a</parent><child>c</child></joint>"
               "<joint name='j3' type='revolute'><parent>c</parent><child>a</child></joint>"
               "</model>");
  for (const auto& x : w.warnings) std::cout << "[joints] " << x << "\n";
  ASSERT_EQ(w.warnings.size(), 3u) << w.allWarnings();
  EXPECT_NE(w.warnings[0].find("joint 'ball' (ball) is not simulated and is held fixed"), std::string::npos);
  EXPECT_NE(w.warnings[1].find("joint 'j2': link 'c' is already the child of joint 'j1'"), std::string::npos);
  EXPECT_NE(w.warnings[2].find("joint 'j3' closes a loop"), std::string::npos);
  const PhysicsRobot& m = w.model("m");
  EXPECT_EQ(m.tree().bodies.size(), 2u);  // a + b (ball held fixed); c on j1
  ASSERT_EQ(m.joints().size(), 1u);
  EXPECT_EQ(m.joints()[0].name, "j1");
}

}  // namespace
}  // namespace tianracer_sim
