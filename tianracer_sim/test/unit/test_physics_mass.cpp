// Mass properties and fixed-joint merging, against numbers worked out by hand.
#include <gtest/gtest.h>

#include <cmath>

#include <urdf_parser/urdf_parser.h>

#include "tianracer_sim/physics/mass_properties.h"
#include "tianracer_sim/physics/rigid_tree.h"

#include "common_test_support.h"

namespace tianracer_sim {
namespace {

Eigen::Isometry3d pose(const Eigen::Vector3d& p, double yaw = 0.0) {
  Eigen::Isometry3d X = Eigen::Isometry3d::Identity();
  X.linear() = Eigen::AngleAxisd(yaw, Eigen::Vector3d::UnitZ()).toRotationMatrix();
  X.translation() = p;
  return X;
}

MassProperties body(double m, const Eigen::Vector3d& com, const Eigen::Vector3d& diag) {
  MassProperties mp;
  mp.mass = m;
  mp.com = com;
  mp.inertia = diag.asDiagonal();
  return mp;
}

// The PhysicsError text of building the tree of `urdf` ("(no error)" if it builds).
std::string treeError(const urdf::ModelInterface& urdf) {
  return test::errorText<PhysicsError>([&] { buildRigidTree(urdf, {}); }, "(no error)");
}

TEST(MassProperties, RotatedOffsetChild) {
  // A: 2 kg at the origin, diag(1, 2, 3). B: 1 kg, diag(0.1, 0.2, 0.3) in its own frame, which
  // sits at (1, 0, 0) rotated +90 deg about z (B's x along A's y, so B's Ixx <-> Iyy in A).
  // COM = (1/3, 0, 0); offsets along x add m d^2 to Iyy and Izz: 2 (1/3)^2 + 1 (2/3)^2 = 2/3.
  const MassProperties a = body(2.0, Eigen::Vector3d::Zero(), {1.0, 2.0, 3.0});
  const MassProperties b_B = body(1.0, Eigen::Vector3d::Zero(), {0.1, 0.2, 0.3});
  const MassProperties c =
      combineMassProperties(a, transformMassProperties(b_B, pose({1, 0, 0}, M_PI / 2)));
  EXPECT_DOUBLE_EQ(c.mass, 3.0);
  EXPECT_TRUE(c.com.isApprox(Eigen::Vector3d(1.0 / 3.0, 0, 0), 1e-15));
  Eigen::Matrix3d expected = Eigen::Vector3d(1.2, 2.1 + 2.0 / 3.0, 3.3 + 2.0 / 3.0).asDiagonal();
  EXPECT_LT((c.inertia - expected).cwiseAbs().maxCoeff(), 1e-14) << c.inertia;
}

TEST(MassProperties, DiagonalOffsetGivesProductsOfInertia) {
  // B (1 kg, diag(0.1, 0.2, 0.3)) at (1, 1, 0): COM (1/3, 1/3, 0).
  // A: d = (-1/3, -1/3, 0): 2 (d.d 1 - d d^T) -> xx 2/9, yy 2/9, zz 4/9, xy -2/9.
  // B: d = (2/3, 2/3, 0):   1 (d.d 1 - d d^T) -> xx 4/9, yy 4/9, zz 8/9, xy -4/9.
  const MassProperties c = combineMassProperties(
      body(2.0, Eigen::Vector3d::Zero(), {1.0, 2.0, 3.0}),
      body(1.0, Eigen::Vector3d(1, 1, 0), {0.1, 0.2, 0.3}));
  Eigen::Matrix3d expected;
  expected << 1.1 + 2.0 / 3.0, -2.0 / 3.0, 0,  //
      -2.0 / 3.0, 2.2 + 2.0 / 3.0, 0,          //
      0, 0, 3.3 + 4.0 / 3.0;
  EXPECT_TRUE(c.com.isApprox(Eigen::Vector3d(1.0 / 3.0, 1.0 / 3.0, 0), 1e-15));
  EXPECT_LT((c.inertia - expected).cwiseAbs().maxCoeff(), 1e-14) << c.inertia;

  // Principal axes: a rotation that diagonalises it; the z axis (already principal) survives.
  const PrincipalInertia p = principalInertia(c.inertia);
  EXPECT_NEAR(p.R.determinant(), 1.0, 1e-12);
  const Eigen::Matrix3d back = p.R * p.moments.asDiagonal() * p.R.transpose();
  EXPECT_LT((back - c.inertia).cwiseAbs().maxCoeff(), 1e-12);
  EXPECT_NEAR(p.moments.sum(), c.inertia.trace(), 1e-12);
  // 2x2 block [[a, b], [b, d]]: eigenvalues (a+d)/2 +- sqrt(((a-d)/2)^2 + b^2).
  const double a = expected(0, 0), d = expected(1, 1), bxy = expected(0, 1);
  const double lo = 0.5 * (a + d) - std::sqrt(0.25 * (a - d) * (a - d) + bxy * bxy);
  EXPECT_NEAR(p.moments.minCoeff(), lo, 1e-12);
}

TEST(MassProperties, DiagonalInertiaKeepsItsAxes) {
  const PrincipalInertia p = principalInertia(Eigen::Vector3d(3.0, 1.0, 2.0).asDiagonal());
  EXPECT_TRUE(p.R.isIdentity());
  EXPECT_TRUE(p.moments.isApprox(Eigen::Vector3d(3.0, 1.0, 2.0)));
}

TEST(MassProperties, MasslessPartsAddNothing) {
  const MassProperties a = body(2.0, Eigen::Vector3d(1, 2, 3), {1, 1, 1});
  const MassProperties c = combineMassProperties(MassProperties(), a);
  EXPECT_EQ(c.mass, 2.0);
  EXPECT_TRUE(c.com.isApprox(a.com));
}

TEST(MassProperties, PhysicalInertia) {
  EXPECT_TRUE(isPhysicalInertia(Eigen::Vector3d(1, 1, 1).asDiagonal()));
  EXPECT_TRUE(isPhysicalInertia(Eigen::Vector3d(1, 1, 2).asDiagonal()));   // thin disc: equality
  EXPECT_FALSE(isPhysicalInertia(Eigen::Vector3d(1, 1, 2.1).asDiagonal()));  // triangle inequality
  EXPECT_FALSE(isPhysicalInertia(Eigen::Vector3d(1, 0, 1).asDiagonal()));
  EXPECT_FALSE(isPhysicalInertia(Eigen::Vector3d(1, -1, 1).asDiagonal()));
}

// base_link (massless) -fixed-> chassis -fixed(rotated)-> sensor -revolute-> flap.
const char* kTreeUrdf = R"(<?xml version="1.0"?>
<robot name="t">
  <link name="base_link"/>
  <link name="chassis">
    <inertial><origin xyz="0.1 0 0.05"/><mass value="4"/>
      <inertia ixx="0.01" ixy="0" ixz="0" iyy="0.02" iyz="0" izz="0.03"/></inertial>
    <collision><geometry><box size="0.4 0.2 0.1"/></geometry></collision>
  </link>
  <joint name="chassis_joint" type="fixed">
    <parent link="base_link"/><child link="chassis"/><origin xyz="0 0 0.02"/>
  </joint>
  <link name="sensor">
    <inertial><origin xyz="0.1 0 0" rpy="0 0 1.5707963267948966"/><mass value="1"/>
      <inertia ixx="0.001" ixy="0" ixz="0" iyy="0.002" iyz="0" izz="0.003"/></inertial>
  </link>
  <joint name="sensor_joint" type="fixed">
    <parent link="chassis"/><child link="sensor"/>
    <origin xyz="0.2 0 0.1" rpy="0 0 1.5707963267948966"/>
  </joint>
  <link name="flap">
    <inertial><mass value="0.5"/>
      <inertia ixx="0.001" ixy="0" ixz="0" iyy="0.001" iyz="0" izz="0.001"/></inertial>
  </link>
  <joint name="flap_joint" type="revolute">
    <parent link="sensor"/><child link="flap"/><origin xyz="0 0.1 0"/>
    <axis xyz="0 0 2"/><limit lower="-0.5" upper="0.5" effort="3" velocity="4"/>
    <dynamics damping="0.2" friction="0.1"/>
  </joint>
</robot>)";

TEST(RigidTree, MergesFixedChildrenByHand) {
  const auto urdf = urdf::parseURDF(kTreeUrdf);
  ASSERT_TRUE(urdf);
  const RigidTree tree = buildRigidTree(*urdf, {});
  ASSERT_EQ(tree.bodies.size(), 2u);
  const TreeBody& base = tree.bodies[0];
  EXPECT_EQ(base.merged_links, (std::vector<std::string>{"base_link", "chassis", "sensor"}));

  // chassis COM in base_link: (0.1, 0, 0.07), 4 kg.
  // sensor frame in base_link: (0.2, 0, 0.12), yaw 90; its COM at sensor (0.1, 0, 0) -> base
  // (0.2, 0.1, 0.12); its inertial frame has yaw 90 too (total 180 deg): diag unchanged.
  // COM = (4 (0.1, 0, 0.07) + 1 (0.2, 0.1, 0.12)) / 5 = (0.12, 0.02, 0.08).
  EXPECT_DOUBLE_EQ(base.mass.mass, 5.0);
  EXPECT_TRUE(base.mass.com.isApprox(Eigen::Vector3d(0.12, 0.02, 0.08), 1e-12)) << base.mass.com;
  // Offsets from the COM: chassis d1 = (-0.02, -0.02, -0.01), sensor d2 = (0.08, 0.08, 0.04).
  auto pa = [](double m, const Eigen::Vector3d& d) {
    return Eigen::Matrix3d(m * (d.squaredNorm() * Eigen::Matrix3d::Identity() - d * d.transpose()));
  };
  const Eigen::Matrix3d expected = Eigen::Vector3d(0.011, 0.022, 0.033).asDiagonal().toDenseMatrix() +
                                   pa(4.0, {-0.02, -0.02, -0.01}) + pa(1.0, {0.08, 0.08, 0.04});
  // By hand: xx = 0.011 + 4 (0.0004 + 0.0001) + (0.0064 + 0.0016) = 0.011 + 0.002 + 0.008 = 0.021
  EXPECT_NEAR(expected(0, 0), 0.021, 1e-15);
  EXPECT_LT((base.mass.inertia - expected).cwiseAbs().maxCoeff(), 1e-15) << base.mass.inertia;
  // xy = -(4 * 0.0004 + 1 * 0.0064) = -0.008
  EXPECT_NEAR(base.mass.inertia(0, 1), -0.008, 1e-15);

  const TreeBody& flap = tree.bodies[1];
  EXPECT_EQ(flap.parent, 0);
  EXPECT_EQ(flap.joint, "flap_joint");
  EXPECT_EQ(flap.joint_type, TreeJointType::kRevolute);
  // Joint frame in base_link: sensor pose * (0, 0.1, 0) = (0.2 - 0.1, 0, 0.12), yaw 90.
  EXPECT_TRUE(flap.X_PB.translation().isApprox(Eigen::Vector3d(0.1, 0.0, 0.12), 1e-12));
  EXPECT_TRUE(flap.X_PB.linear().isApprox(
      Eigen::AngleAxisd(M_PI / 2, Eigen::Vector3d::UnitZ()).toRotationMatrix(), 1e-12));
  EXPECT_TRUE(flap.axis_B.isApprox(Eigen::Vector3d::UnitZ()));  // normalised
  EXPECT_TRUE(flap.has_position_limits);
  EXPECT_EQ(flap.lower, -0.5);
  EXPECT_EQ(flap.effort_limit, 3.0);
  EXPECT_EQ(flap.damping, 0.2);
  EXPECT_EQ(flap.friction, 0.1);

  ASSERT_EQ(base.collisions.size(), 1u);
  EXPECT_EQ(base.collisions[0].link, "chassis");
  EXPECT_TRUE(base.collisions[0].X_BG.translation().isApprox(Eigen::Vector3d(0, 0, 0.02)));
  EXPECT_TRUE(tree.links.at("sensor").second.translation().isApprox(Eigen::Vector3d(0.2, 0, 0.12)));
}

TEST(RigidTree, MasslessMovingLinkIsAnError) {
  std::string xml = kTreeUrdf;
  const std::string flap_inertial =
      R"(<inertial><mass value="0.5"/>
      <inertia ixx="0.001" ixy="0" ixz="0" iyy="0.001" iyz="0" izz="0.001"/></inertial>)";
  xml.replace(xml.find(flap_inertial), flap_inertial.size(), "");
  const auto urdf = urdf::parseURDF(xml);
  ASSERT_TRUE(urdf);
  const std::string e = treeError(*urdf);
  EXPECT_NE(e.find("'flap'"), std::string::npos) << e;
  EXPECT_NE(e.find("flap_joint"), std::string::npos) << e;
}

TEST(RigidTree, UnresolvedMeshNamesLinkAndUri) {
  const auto urdf = urdf::parseURDF(R"(<robot name="m"><link name="a">
    <inertial><mass value="1"/><inertia ixx="1" ixy="0" ixz="0" iyy="1" iyz="0" izz="1"/></inertial>
    <collision><geometry><mesh filename="package://nowhere/x.stl"/></geometry></collision>
    </link></robot>)");
  ASSERT_TRUE(urdf);
  const std::string e = treeError(*urdf);
  EXPECT_NE(e.find("link 'a'"), std::string::npos) << e;
  EXPECT_NE(e.find("package://nowhere/x.stl"), std::string::npos) << e;
}

}  // namespace
}  // namespace tianracer_sim
