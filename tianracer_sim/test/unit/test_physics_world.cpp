// PhysicsWorld on small hand-made robots: free fall, joint conventions, contacts, commands,
// determinism and state setting. The tianracer itself is in test_physics_tianracer.cpp.
#include <gtest/gtest.h>

#include <cmath>
#include <iostream>
#include <limits>

#include <urdf_parser/urdf_parser.h>

#include "physics_test_support.h"
#include "tianracer_sim/physics/world.h"

namespace tianracer_sim {
namespace {

const std::string kCube = std::string(TEST_DATA_DIR) + "/physics/cube_10cm.stl";

TestRobot modelFrom(const std::string& xml) { return parseTestRobot(xml); }

std::string boxRobot(const std::string& collision) {
  return R"(<robot name="box"><link name="base_link">
    <inertial><origin xyz="0 0 0"/><mass value="2"/>
      <inertia ixx="0.00333" ixy="0" ixz="0" iyy="0.00333" iyz="0" izz="0.00333"/></inertial>
    <collision>)" + collision + R"(</collision></link></robot>)";
}

// The arm as a pendulum hinged at the base's origin, +-1 rad, with a spinner on a continuous
// joint about x at its end.
const std::string kArm = armRobot("0 0 0", "1", R"(  <link name="spinner">
    <inertial><mass value="0.1"/><inertia ixx="0.001" ixy="0" ixz="0" iyy="0.001" iyz="0" izz="0.001"/></inertial>
  </link>
  <joint name="spin" type="continuous">
    <parent link="arm"/><child link="spinner"/><origin xyz="1 0 0"/><axis xyz="1 0 0"/>
  </joint>
)");

TEST(PhysicsWorld, FreeFallMatchesSemiImplicitEuler) {
  PhysicsOptions o;
  o.ground_plane = false;
  PhysicsWorld w(o);
  PhysicsRobot& r = w.robot(addTestRobot(w, modelFrom(boxRobot("<geometry><box size='0.1 0.1 0.1'/></geometry>")),
                                       at(0, 0, 10), "box"));
  const int n = 1000;
  for (int k = 0; k < n; ++k) w.step();
  const double g = 9.8, dt = o.dt, t = n * dt;
  // Bullet integrates v += g dt, then x += v dt: z = z0 - g dt^2 n (n + 1) / 2, which is the
  // analytic z0 - g t^2 / 2 minus g dt t / 2 (4.9 mm after 1 s).
  const double z_discrete = 10.0 - g * dt * dt * n * (n + 1) / 2.0;
  const double z_analytic = 10.0 - 0.5 * g * t * t;
  const double z = r.basePose().translation().z();
  std::cout << "[free fall 1 s] z = " << z << " m, analytic " << z_analytic << ", discrete "
            << z_discrete << ", v = " << r.baseTwist().linear.z() << " m/s\n";
  EXPECT_NEAR(z, z_discrete, 1e-9);
  EXPECT_NEAR(z, z_analytic, 0.5 * g * dt * t + 1e-9);
  EXPECT_NEAR(r.baseTwist().linear.z(), -g * t, 1e-9);
  EXPECT_NEAR(w.time(), 1.0, 1e-12);
  EXPECT_EQ(w.stepCount(), 1000u);
  // Energy is conserved up to the integrator's O(dt) error.
  EXPECT_NEAR(r.kineticEnergy(), 0.5 * 2.0 * g * g * t * t, 1e-6);
}

TEST(PhysicsWorld, BoxRestsOnGroundWithoutMarginGap) {
  for (const std::string& col : {std::string("<geometry><box size='0.1 0.1 0.1'/></geometry>"),
                                 "<geometry><mesh filename='" + kCube + "'/></geometry>"}) {
    PhysicsWorld w;
    PhysicsRobot& r = w.robot(addTestRobot(w, modelFrom(boxRobot(col)), at(0, 0, 0.06), "box"));
    for (int k = 0; k < 2000; ++k) w.step();
    const double z = r.basePose().translation().z();
    std::cout << "[resting 10 cm cube] " << (col.find("mesh") != std::string::npos ? "mesh hull" : "box")
              << ": centre z = " << z << " m (0.05 exact)\n";
    // A Bullet default margin would float it 4 cm up; ours is inside the shape.
    EXPECT_NEAR(z, 0.05, 1e-4) << col;
    EXPECT_LT(r.baseTwist().linear.norm(), 1e-4);
  }
}

TEST(PhysicsWorld, StaticShapesCollide) {
  PhysicsWorld w;
  StaticShape table;
  table.name = "table";
  table.shape.type = ShapeType::kBox;
  table.shape.size = Eigen::Vector3d(1.0, 1.0, 0.2);
  table.X_WS = at(0, 0, 0.1);
  EXPECT_EQ(w.addStaticShape(table), 0);
  StaticShape mesh;
  mesh.name = "cube";
  mesh.shape.type = ShapeType::kMesh;
  mesh.shape.mesh_path = kCube;
  mesh.X_WS = at(2, 0, 0.05);
  EXPECT_EQ(w.addStaticShape(mesh), 1);
  PhysicsRobot& on_table = w.robot(addTestRobot(w, 
      modelFrom(boxRobot("<geometry><sphere radius='0.05'/></geometry>")), at(0, 0, 0.3), "ball"));
  PhysicsRobot& on_mesh = w.robot(addTestRobot(w, 
      modelFrom(boxRobot("<geometry><sphere radius='0.05'/></geometry>")), at(2, 0, 0.3), "ball2"));
  for (int k = 0; k < 1500; ++k) w.step();
  EXPECT_NEAR(on_table.basePose().translation().z(), 0.25, 2e-4);
  EXPECT_NEAR(on_mesh.basePose().translation().z(), 0.15, 2e-4);
  EXPECT_GT(on_table.contactCount("base_link"), 0);
}

TEST(PhysicsWorld, RobotsCollideWithEachOther) {
  PhysicsWorld w(weightless());
  const TestRobot ball = modelFrom(boxRobot("<geometry><sphere radius='0.05'/></geometry>"));
  PhysicsRobot& a = w.robot(addTestRobot(w, ball, at(0, 0, 0), "a"));
  PhysicsRobot& b = w.robot(addTestRobot(w, ball, at(0.3, 0, 0), "b"));
  EXPECT_THROW(addTestRobot(w, ball, at(1, 0, 0), "a"), PhysicsError);  // names are unique
  a.setBaseTwist({Eigen::Vector3d(1, 0, 0), Eigen::Vector3d::Zero()});
  for (int k = 0; k < 400; ++k) w.step();
  // Equal masses, no restitution: they end up moving together at 0.5 m/s.
  EXPECT_NEAR(a.baseTwist().linear.x(), 0.5, 1e-3);
  EXPECT_NEAR(b.baseTwist().linear.x(), 0.5, 1e-3);
  EXPECT_EQ(w.robotId("b"), 1);
  EXPECT_EQ(w.robotId("zz"), -1);
}

TEST(PhysicsWorld, JointConventionsAndLinkPoses) {
  PhysicsWorld w(weightless());
  PhysicsRobot& r = w.robot(addTestRobot(w, modelFrom(kArm), at(1, 2, 3, 0.5), "arm"));
  ASSERT_EQ(r.joints().size(), 2u);
  const int hinge = r.jointIndex("hinge"), spin = r.jointIndex("spin");
  EXPECT_EQ(r.joints()[hinge].type, JointType::kRevolute);
  EXPECT_EQ(r.joints()[spin].type, JointType::kContinuous);
  EXPECT_EQ(r.joints()[hinge].effort_limit, 5.0);
  EXPECT_EQ(r.joints()[spin].motor_effort, 10.0);  // no URDF limit: the documented default
  EXPECT_EQ(r.jointIndex("nope"), -1);

  // URDF: child = parent * origin * Rot(axis, q).
  r.setJointState(hinge, 0.4, 0.0);
  const Eigen::Isometry3d X_WA = at(1, 2, 3, 0.5) * at(0, 0, 0, 0.3) *
                                 Eigen::Isometry3d(Eigen::AngleAxisd(0.4, Eigen::Vector3d::UnitY()));
  EXPECT_TRUE(r.linkPose("arm").isApprox(X_WA, 1e-12)) << r.linkPose("arm").matrix();
  const Eigen::Isometry3d X_WS = X_WA * at(1, 0, 0);
  EXPECT_TRUE(r.linkPose("spinner").isApprox(X_WS, 1e-12));
  EXPECT_TRUE(r.basePose().isApprox(at(1, 2, 3, 0.5), 1e-12));
  EXPECT_THROW(r.linkPose("nope"), PhysicsError);
  EXPECT_EQ(r.linkNames(), (std::vector<std::string>{"base_link", "arm", "spinner"}));
}

TEST(PhysicsWorld, JointLimitHoldsAndEffortIsClamped) {
  PhysicsWorld w(weightless());
  PhysicsRobot& r = w.robot(addTestRobot(w, modelFrom(kArm), at(0, 0, 0), "arm"));
  const int hinge = r.jointIndex("hinge");
  r.setJointEffort(hinge, 100.0);  // clamped to 5
  for (int k = 0; k < 2000; ++k) w.step();
  EXPECT_EQ(r.jointEffort(hinge), 5.0);
  EXPECT_NEAR(r.jointPosition(hinge), 1.0, 0.01);  // at the upper limit
  r.setJointEffort(hinge, -5.0);
  for (int k = 0; k < 2000; ++k) w.step();
  EXPECT_NEAR(r.jointPosition(hinge), -1.0, 0.01);
}

TEST(PhysicsWorld, VelocityMotorReachesTargetWithinItsEffort) {
  PhysicsWorld w(weightless());
  PhysicsRobot& r = w.robot(addTestRobot(w, modelFrom(kArm), at(0, 0, 0), "arm"));
  const int spin = r.jointIndex("spin");
  // Izz 0.001 about x; 0.01 N m -> 10 rad/s^2: 20 rad/s needs 2 s.
  r.setJointVelocityTarget(spin, 20.0, 0.01);
  for (int k = 0; k < 1000; ++k) w.step();
  EXPECT_NEAR(r.jointVelocity(spin), 10.0, 0.5);
  EXPECT_NEAR(std::abs(r.jointEffort(spin)), 0.01, 1e-6);
  for (int k = 0; k < 2000; ++k) w.step();
  EXPECT_NEAR(r.jointVelocity(spin), 20.0, 1e-3);
  r.clearJointCommand(spin);
  for (int k = 0; k < 100; ++k) w.step();
  EXPECT_NEAR(r.jointVelocity(spin), 20.0, 1e-3);  // free again: keeps spinning
  EXPECT_EQ(r.jointEffort(spin), 0.0);
}

#ifdef NDEBUG  // debug builds assert on non-finite commands instead
TEST(PhysicsWorld, NonFiniteCommandsNeverReachBullet) {
  PhysicsWorld w;
  PhysicsRobot& r = w.robot(addTestRobot(w, modelFrom(kArm), at(0, 0, 1), "arm"));
  const double nan = std::numeric_limits<double>::quiet_NaN();
  const double inf = std::numeric_limits<double>::infinity();
  r.setJointEffort(0, nan);
  r.setJointEffort(0, inf);
  r.setJointVelocityTarget(1, nan);
  r.setJointVelocityTarget(1, 1.0, inf);
  r.setBaseTwist({Eigen::Vector3d(nan, 0, 0), Eigen::Vector3d::Zero()});
  EXPECT_EQ(r.rejectedCommands(), 5u);
  for (int k = 0; k < 10; ++k) w.step();
  EXPECT_TRUE(r.basePose().matrix().allFinite());
  EXPECT_TRUE(std::isfinite(r.jointPosition(0)));
}
#endif

TEST(PhysicsWorld, ResetToSpawnAndSetState) {
  PhysicsWorld w;
  PhysicsRobot& r = w.robot(addTestRobot(w, modelFrom(kArm), at(0, 0, 1), "arm"));
  r.setJointEffort(0, 2.0);
  r.setBaseTwist({Eigen::Vector3d(1, 0, 0), Eigen::Vector3d(0, 0, 1)});
  for (int k = 0; k < 300; ++k) w.step();
  EXPECT_GT(r.kineticEnergy(), 0.1);
  r.resetToSpawn();
  EXPECT_TRUE(r.basePose().isApprox(at(0, 0, 1), 1e-12));
  EXPECT_EQ(r.jointPosition(0), 0.0);
  EXPECT_EQ(r.jointVelocity(0), 0.0);
  EXPECT_EQ(r.kineticEnergy(), 0.0);
  EXPECT_EQ(r.jointEffort(0), 0.0);

  const Twist t{Eigen::Vector3d(0.5, -0.2, 0.1), Eigen::Vector3d(0.1, 0.2, 0.3)};
  r.setBasePose(at(3, 4, 5, 1.0));
  r.setBaseTwist(t);
  EXPECT_TRUE(r.basePose().isApprox(at(3, 4, 5, 1.0), 1e-12));
  EXPECT_TRUE(r.baseTwist().linear.isApprox(t.linear, 1e-12));
  EXPECT_TRUE(r.baseTwist().angular.isApprox(t.angular, 1e-12));
}

// set_model_state's velocity (Gazebo's Model::SetLinearVel/SetAngularVel give every link the
// twist): the joints stop. setBaseTwist (set_link_state's rigid move) keeps their rates.
TEST(PhysicsWorld, ModelTwistStopsTheJointsBaseTwistKeepsThem) {
  PhysicsWorld w;
  PhysicsRobot& r = w.robot(addTestRobot(w, modelFrom(kArm), at(0, 0, 1), "arm"));
  r.setJointState(0, 0.3, 2.0);
  const Twist t{Eigen::Vector3d(0.5, -0.2, 0.1), Eigen::Vector3d(0.1, 0.2, 0.3)};
  r.setBaseTwist(t);
  EXPECT_EQ(r.jointVelocity(0), 2.0);
  r.setModelTwist(t);
  EXPECT_EQ(r.jointVelocity(0), 0.0);
  EXPECT_EQ(r.jointPosition(0), 0.3);
  EXPECT_TRUE(r.baseTwist().linear.isApprox(t.linear, 1e-12));
  EXPECT_TRUE(r.baseTwist().angular.isApprox(t.angular, 1e-12));
  // Not finite: refused and counted, nothing changes.
  r.setJointState(0, 0.3, 2.0);
  const std::uint64_t rejected = r.rejectedCommands();
  r.setModelTwist({Eigen::Vector3d(std::nan(""), 0, 0), Eigen::Vector3d::Zero()});
  EXPECT_EQ(r.rejectedCommands(), rejected + 1);
  EXPECT_EQ(r.jointVelocity(0), 2.0);
  EXPECT_TRUE(r.baseTwist().linear.isApprox(t.linear, 1e-12));
}

// Same inputs, same bits: two worlds stepped side by side.
TEST(PhysicsWorld, Deterministic) {
  auto run = [](std::vector<double>* out) {
    PhysicsWorld w;
    const TestRobot m = modelFrom(kArm);
    PhysicsRobot& a = w.robot(addTestRobot(w, m, at(0, 0, 0.8), "a"));
    PhysicsRobot& b = w.robot(addTestRobot(w, m, at(0.3, 0.1, 1.5, 0.7), "b"));
    for (int k = 0; k < 3000; ++k) {
      a.setJointEffort(0, std::sin(k * 0.01));
      b.setJointVelocityTarget(1, 5.0);
      w.step();
    }
    for (PhysicsRobot* r : {&a, &b}) {
      const Eigen::Isometry3d X = r->basePose();
      out->insert(out->end(), X.data(), X.data() + 16);
      out->push_back(r->jointPosition(0));
      out->push_back(r->jointVelocity(1));
    }
  };
  std::vector<double> x, y;
  run(&x);
  run(&y);
  ASSERT_EQ(x.size(), y.size());
  for (std::size_t i = 0; i < x.size(); ++i) EXPECT_EQ(x[i], y[i]) << i;
}

// Anisotropic friction: mu1 along fdir1 = x, mu2 across; the ground (mu 100 / 50) is stronger,
// so min() leaves the box's own values: sliding decelerates at mu g in each direction.
TEST(PhysicsWorld, AnisotropicSlidingFriction) {
  // A flat plate: a cube at mu 1 would be on the verge of tipping over its front edge.
  TestRobot m = modelFrom(boxRobot("<geometry><box size='0.2 0.2 0.02'/></geometry>"));
  SurfaceParams e;
  e.mu1 = 1.0;
  e.mu2 = 0.2;
  e.fdir1 = Eigen::Vector3d::UnitX();
  m.surfaces["base_link"] = e;
  for (int dir = 0; dir < 2; ++dir) {
    PhysicsWorld w;
    PhysicsRobot& r = w.robot(addTestRobot(w, m, at(0, 0, 0.01), "box"));
    for (int k = 0; k < 200; ++k) w.step();  // settle
    Twist t;
    t.linear = dir == 0 ? Eigen::Vector3d(1, 0, 0) : Eigen::Vector3d(0, 1, 0);
    r.setBaseTwist(t);
    for (int k = 0; k < 50; ++k) w.step();
    const double mu = dir == 0 ? 1.0 : 0.2;
    const double v = r.baseTwist().linear.head<2>().norm();
    std::cout << "[sliding box] along " << (dir == 0 ? "fdir1 (mu1 1.0)" : "fdir2 (mu2 0.2)")
              << ": v after 50 ms = " << v << " m/s, Coulomb " << 1.0 - mu * 9.8 * 0.05 << "\n";
    EXPECT_NEAR(v, 1.0 - mu * 9.8 * 0.05, 0.01);
  }
}

/// A 0.2 m box with mu 0.5 on Gazebo's ground (mu 100), rested for 0.2 s, then (after
/// `rest_steps` more steps) pushed diagonally at 1 m/s for 0.1 s. Returns its deceleration
/// (m/s^2) and its heading of travel; `rest_drift` is how far it moved while resting.
struct DiagonalSlide {
  double decel, heading, rest_drift;
};
DiagonalSlide slideDiagonally(const PhysicsOptions& options, int rest_steps) {
  TestRobot m = modelFrom(boxRobot("<geometry><box size='0.2 0.2 0.02'/></geometry>"));
  SurfaceParams e;
  e.mu1 = e.mu2 = 0.5;
  m.surfaces["base_link"] = e;
  PhysicsWorld w(options);
  PhysicsRobot& r = w.robot(addTestRobot(w, m, at(0, 0, 0.01, 0.3), "box"));
  for (int k = 0; k < 200; ++k) w.step();
  const Eigen::Vector3d p_rest = r.basePose().translation();
  for (int k = 0; k < rest_steps; ++k) w.step();
  DiagonalSlide d{};
  d.rest_drift = (r.basePose().translation() - p_rest).norm();
  r.setBaseTwist({Eigen::Vector3d(0.6, 0.8, 0), Eigen::Vector3d::Zero()});
  for (int k = 0; k < 100; ++k) w.step();
  d.decel = (1.0 - r.baseTwist().linear.head<2>().norm()) / 0.1;
  d.heading = std::atan2(r.baseTwist().linear.y(), r.baseTwist().linear.x());
  return d;
}

// Ground friction combines by min(): the box decelerates at 0.5 g (a product rule would give
// 50 g). Bullet solves the two friction rows and then clamps them to the cone, which leaves a
// diagonal slide up to ~10% below Coulomb (axis-aligned slides are exact, see above).
TEST(PhysicsWorld, FrictionCombinesByMinimum) {
  const DiagonalSlide d = slideDiagonally(PhysicsOptions(), 0);
  std::cout << "[sliding box] diagonal, mu 0.5: deceleration " << d.decel << " m/s^2, Coulomb "
            << 0.5 * 9.8 << "\n";
  EXPECT_NEAR(d.decel, 0.5 * 9.8, 0.1 * 0.5 * 9.8);
  EXPECT_NEAR(d.heading, std::atan2(0.8, 0.6), 0.05);
}

// SDF cone_model (FrictionModel::kCone): a sliding contact's friction rows lie along its slip,
// so the same diagonal slide decelerates at Coulomb's mu g along its own direction; at rest the
// contacts stick, and the box stays where it is.
TEST(PhysicsWorld, ConeModelSlidesDiagonallyAtCoulomb) {
  PhysicsOptions o;
  o.friction_model = FrictionModel::kCone;
  const DiagonalSlide d = slideDiagonally(o, 200);
  std::cout << "[sliding box] diagonal, mu 0.5, cone_model: deceleration " << d.decel
            << " m/s^2, Coulomb " << 0.5 * 9.8 << "\n";
  EXPECT_LT(d.rest_drift, 1e-6);
  EXPECT_NEAR(d.decel, 0.5 * 9.8, 0.02 * 0.5 * 9.8);
  EXPECT_NEAR(d.heading, std::atan2(0.8, 0.6), 0.02);
}

// URDF <dynamics damping friction>: viscous decay and Coulomb deceleration of a free joint.
TEST(PhysicsWorld, JointDampingAndFriction) {
  const PhysicsOptions o = weightless();
  std::string xml = kArm;
  const std::string spin_end = "<axis xyz=\"1 0 0\"/>\n  </joint>";
  for (int variant = 0; variant < 2; ++variant) {
    std::string v = xml;
    v.replace(v.find(spin_end), spin_end.size(),
              variant == 0 ? "<axis xyz=\"1 0 0\"/><dynamics damping=\"0.001\"/>\n  </joint>"
                           : "<axis xyz=\"1 0 0\"/><dynamics friction=\"0.002\"/>\n  </joint>");
    PhysicsWorld w(o);
    PhysicsRobot& r = w.robot(addTestRobot(w, modelFrom(v), at(0, 0, 0), "arm"));
    const int spin = r.jointIndex("spin");
    r.setJointState(spin, 0.0, 10.0);
    for (int k = 0; k < 500; ++k) w.step();
    // Spinner Ixx 0.001 (the arm is held by the 10 kg base, hardly moves):
    // damping 0.001 -> w = 10 exp(-t); friction 0.002 -> w = 10 - 2 t.
    const double expected = variant == 0 ? 10.0 * std::exp(-0.5) : 10.0 - 2.0 * 0.5;
    EXPECT_NEAR(r.jointVelocity(spin), expected, 0.02 * expected) << variant;
  }
}

// A root link named "world" pins the robot (URDF convention): the arm hangs from a fixed base.
TEST(PhysicsWorld, WorldRootIsFixed) {
  std::string xml = kArm;
  xml.replace(xml.find("<robot name=\"arm\">"), 17, "<robot name=\"arm\"><link name=\"world\"/>"
              "<joint name=\"pin\" type=\"fixed\"><parent link=\"world\"/><child link=\"base_link\"/></joint>");
  PhysicsOptions o;
  o.ground_plane = false;
  PhysicsWorld w(o);
  PhysicsRobot& r = w.robot(addTestRobot(w, modelFrom(xml), at(0, 0, 1), "pinned"));
  for (int k = 0; k < 1000; ++k) w.step();
  EXPECT_TRUE(r.basePose().isApprox(at(0, 0, 1), 1e-12));
  EXPECT_NEAR(r.jointPosition(r.jointIndex("hinge")), 1.0, 0.01);  // swung down onto its limit
}

}  // namespace
}  // namespace tianracer_sim
