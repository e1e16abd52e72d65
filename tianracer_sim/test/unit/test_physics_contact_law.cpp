// The contact law on its own: springs in series, dampers in parallel, the tyre, which sides'
// recovery limits count, ERP/CFM and the capped correction.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>

#include "tianracer_sim/physics/contact_law.h"

namespace tianracer_sim {
namespace {

Surface surface(double kp, double kd, double max_vel = 0.1, double min_depth = 0.0) {
  Surface s;
  s.kp = kp;
  s.kd = kd;
  s.max_vel = max_vel;
  s.min_depth = min_depth;
  return s;
}

ColliderSurfaces collider(const Surface& s, bool body, bool wheel = false, double kt = 0.0,
                          double ct = 0.0) {
  ColliderSurfaces c;
  c.children.push_back(s);
  c.body = body;
  c.wheel = wheel;
  c.tyre_stiffness = kt;
  c.tyre_damping = ct;
  return c;
}

TEST(ContactLaw, SpringsInSeriesDampersInParallel) {
  const Surface a = surface(1e7, 2.0), b = surface(4e7, 3.0);
  const ContactLaw law = contactLaw(collider(a, true), a, collider(b, false), b);
  EXPECT_TRUE(law.soft);
  EXPECT_DOUBLE_EQ(law.kp, 1.0 / (1.0 / 1e7 + 1.0 / 4e7));  // 8e6
  EXPECT_NEAR(law.kp, 8e6, 1e-6);
  EXPECT_DOUBLE_EQ(law.kd, 5.0);
}

TEST(ContactLaw, RigidDefaultsStayRigid) {
  const Surface a = surface(kRigidKp, 1.0);
  const ContactLaw law = contactLaw(collider(a, true), a, collider(a, false), a);
  EXPECT_DOUBLE_EQ(law.kp, 0.5 * kRigidKp);
  EXPECT_FALSE(law.soft);  // two rigid surfaces: Bullet's rigid contact
}

// Gazebo's depth_camera2.world: a box of kp 1e15, kd 1e13 on the default ground. The damping
// makes it soft (ODE's erp 1e-4 at 1 ms), though its kp is rigid.
TEST(ContactLaw, RigidStiffnessWithHugeDampingIsSoft) {
  const Surface box = surface(1e15, 1e13), ground = surface(kRigidKp, 1.0);
  const ContactLaw law = contactLaw(collider(box, true), box, collider(ground, false), ground);
  EXPECT_TRUE(law.soft);
  const ErpCfm r = softErpCfm(law.kp, law.kd, 1e-3);
  EXPECT_NEAR(r.erp, 1e-4, 1e-6);
  // Below the threshold a rigid kp stays Bullet's rigid contact.
  const Surface damped = surface(kRigidKp, 0.5 * kDampedKd);
  EXPECT_FALSE(contactLaw(collider(damped, true), damped, collider(ground, false), ground).soft);
}

TEST(ContactLaw, TyreIsOneMoreSpringAndDamperOnOneSideOnly) {
  const Surface wheel = surface(1e7, 1.0), ground = surface(kRigidKp, 1.0);
  const ColliderSurfaces w = collider(wheel, true, true, 1e5, 40.0);
  const ColliderSurfaces g = collider(ground, false);
  const ContactLaw law = contactLaw(w, wheel, g, ground);
  const double surfaces = 1.0 / (1.0 / 1e7 + 1.0 / kRigidKp);
  EXPECT_DOUBLE_EQ(law.kp, 1.0 / (1.0 / surfaces + 1.0 / 1e5));
  EXPECT_NEAR(law.kp, 1e5 * 1e7 / (1e5 + 1e7), 1.0);
  EXPECT_DOUBLE_EQ(law.kd, 2.0 + 40.0);
  // Same law with the sides swapped.
  const ContactLaw swapped = contactLaw(g, ground, w, wheel);
  EXPECT_DOUBLE_EQ(swapped.kp, law.kp);
  EXPECT_DOUBLE_EQ(swapped.kd, law.kd);
  // A wheel on a wheel: no tyre, the surfaces only.
  const ContactLaw both = contactLaw(w, wheel, w, wheel);
  EXPECT_DOUBLE_EQ(both.kp, 5e6);
  EXPECT_DOUBLE_EQ(both.kd, 2.0);
}

TEST(ContactLaw, RecoveryLimitsComeFromBodySidesOnly) {
  const Surface a = surface(1e7, 1.0, 0.3, 0.002), b = surface(1e7, 1.0, 0.1, 0.001);
  // Static side b: only a counts.
  ContactLaw law = contactLaw(collider(a, true), a, collider(b, false), b);
  EXPECT_DOUBLE_EQ(law.max_vel, 0.3);
  EXPECT_DOUBLE_EQ(law.min_depth, 0.002);
  // Two bodies: the smaller of each.
  law = contactLaw(collider(a, true), a, collider(b, true), b);
  EXPECT_DOUBLE_EQ(law.max_vel, 0.1);
  EXPECT_DOUBLE_EQ(law.min_depth, 0.001);
  // No body: no limit of its own.
  law = contactLaw(collider(a, false), a, collider(b, false), b);
  EXPECT_TRUE(std::isinf(law.max_vel));
  EXPECT_DOUBLE_EQ(law.min_depth, 0.0);
}

TEST(ContactLaw, ErpCfmAsOde) {
  const double dt = 0.001, kp = 1e5, kd = 40.0;
  const ErpCfm r = softErpCfm(kp, kd, dt);
  EXPECT_DOUBLE_EQ(r.erp, dt * kp / (dt * kp + kd));  // 100 / 140
  EXPECT_DOUBLE_EQ(r.cfm, 1.0 / (dt * kp + kd));
  EXPECT_NEAR(r.erp, 100.0 / 140.0, 1e-15);
}

TEST(ContactLaw, CorrectionIsCappedAndMinDepthLeftAlone) {
  ContactLaw law;
  law.max_vel = 0.1;
  const double dt = 0.001, erp = 0.2;
  // 0.1 mm deep: erp depth / dt = 0.02 m/s < 0.1: Bullet's own row.
  EXPECT_FALSE(cappedErp(law, erp, 1e-4, dt, 100.0).has_value());
  // 10 mm deep: 2 m/s > 0.1 m/s: erp' depth / dt = 0.1 m/s.
  auto e = cappedErp(law, erp, 0.01, dt, 100.0);
  ASSERT_TRUE(e.has_value());
  EXPECT_NEAR(*e * 0.01 / dt, 0.1, 1e-12);
  // The world's cap binds when lower.
  e = cappedErp(law, erp, 0.01, dt, 0.05);
  ASSERT_TRUE(e.has_value());
  EXPECT_NEAR(*e * 0.01 / dt, 0.05, 1e-12);
  // min_depth: only the depth beyond it is corrected.
  law.max_vel = std::numeric_limits<double>::infinity();
  law.min_depth = 0.001;
  e = cappedErp(law, erp, 0.003, dt, 100.0);
  ASSERT_TRUE(e.has_value());
  EXPECT_NEAR(*e * 0.003, erp * 0.002, 1e-15);
  e = cappedErp(law, erp, 0.0005, dt, 100.0);
  ASSERT_TRUE(e.has_value());
  EXPECT_DOUBLE_EQ(*e, 0.0);
  // Not penetrating: nothing.
  EXPECT_FALSE(cappedErp(law, erp, -0.001, dt, 100.0).has_value());
}

TEST(ContactLaw, SurfaceClampsAndFriction) {
  SurfaceParams p;
  p.mu1 = -1.0;
  p.mu2 = 0.4;
  p.kp = 0.0;
  p.kd = -3.0;
  p.fdir1 = Eigen::Vector3d(2, 0, 0);
  p.max_vel = -1.0;
  p.min_depth = -0.5;
  const Eigen::Matrix3d R = Eigen::AngleAxisd(M_PI / 2, Eigen::Vector3d::UnitZ()).toRotationMatrix();
  const Surface s = toSurface(p, R, 0.1);
  EXPECT_EQ(s.mu1, std::numeric_limits<float>::max());  // negative: no limit, as Gazebo
  EXPECT_EQ(s.mu2, 0.4);
  EXPECT_EQ(s.kp, kRigidKp);
  EXPECT_EQ(s.kd, 0.0);
  EXPECT_TRUE(s.has_fdir1);
  EXPECT_NEAR((s.fdir1_C - Eigen::Vector3d::UnitY()).norm(), 0.0, 1e-12);
  EXPECT_TRUE(std::isinf(s.max_vel));  // negative: the world's cap only
  EXPECT_EQ(s.min_depth, 0.0);
  EXPECT_EQ(toSurface(SurfaceParams{}, R, 0.1).max_vel, 0.1);  // unset: the default

  Surface a, b;
  a.mu1 = 1.0, a.mu2 = 0.2;
  b.mu1 = 100.0, b.mu2 = 50.0;
  EXPECT_DOUBLE_EQ(combinedFriction(a, b), 1.0);
  b.mu1 = 0.5;
  EXPECT_DOUBLE_EQ(combinedFriction(a, b), 0.5);
}

}  // namespace
}  // namespace tianracer_sim
