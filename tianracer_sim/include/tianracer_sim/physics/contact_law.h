// The contact law: how two surfaces in contact combine into one normal row (stiffness, damping,
// penetration recovery) and one friction coefficient. Gazebo/ODE's rules plus a tyre spring; see
// docs/physics.md for why each rule is what it is. Bullet-free, so it is tested directly.
#ifndef TIANRACER_SIM_PHYSICS_CONTACT_LAW_H
#define TIANRACER_SIM_PHYSICS_CONTACT_LAW_H

#include <cstdint>
#include <limits>
#include <optional>
#include <vector>

#include <Eigen/Geometry>

namespace tianracer_sim {

/// Surface of a collision (Gazebo <surface> / <gazebo reference> values; defaults are Gazebo's).
struct SurfaceParams {
  double mu1 = 1.0, mu2 = 1.0;
  double kp = 1e12, kd = 1.0;
  Eigen::Vector3d fdir1 = Eigen::Vector3d::Zero();  // in the link/shape frame; zero = none
  /// Penetration recovery of a body's surface (<maxVel>, <minDepth>); static shapes ignore
  /// them (they have no ODE body). Unset max_vel: PhysicsOptions::contact_max_vel; a negative
  /// one: the world's cap only (Gazebo).
  std::optional<double> max_vel;
  double min_depth = 0.0;
  /// Found by the narrowphase (contact sensors see it) but never solved: it pushes nothing
  /// (Gazebo's <collide_without_contact>). On a moving body, when every collision of the body
  /// has it (Bullet's response is per collision object).
  bool collide_without_contact = false;
  /// Gazebo's <collide_without_contact_bitmask> and <collide_bitmask> (ColliderSurfaces).
  std::uint32_t collide_without_contact_bitmask = 1;
  std::uint32_t collide_bitmask = 0xffff;
};

/// SDF's default kp (1e12) and above count as a rigid contact ...
constexpr double kRigidKp = 1e12;
/// ... unless its damping is this or more: then the damping, not the stiffness, sets the
/// contact (ODE's erp = dt kp / (dt kp + kd) is 0.33 or less for two default surfaces at a 1 ms
/// step, and falls as kd grows), and kp/kd are used as for any soft contact. Gazebo's
/// depth_camera2.world gives a box kd 1e13: ODE's erp 1e-4, a box 1 m deep in the ground rises
/// at 0.1 m/s; the rigid row (erp2 0.2) threw it out at max_vel (100 m/s).
constexpr double kDampedKd = 1e9;

/// One collision's surface as the contact law reads it.
struct Surface {
  double mu1 = 1.0, mu2 = 1.0, kp = kRigidKp, kd = 1.0;
  double max_vel = 0.1, min_depth = 0.0;  // bodies only; max_vel infinite: the world's cap
  bool has_fdir1 = false;
  Eigen::Vector3d fdir1_C = Eigen::Vector3d::Zero();  // unit, in the collision object's frame
};

/// The surfaces of one collision object: one per compound child (index), or a single one.
struct ColliderSurfaces {
  std::vector<Surface> children;
  /// A moving body (robot link or free body): ODE would give it a body, static shapes have none.
  bool body = false;
  /// A collider whose shapes are all fitted wheels has a tyre (PhysicsOptions::tyre_*).
  bool wheel = false;
  double tyre_stiffness = 0.0, tyre_damping = 0.0;
  /// Which objects meet at all (WorldModelFilter), Gazebo's per-collision masks
  /// (ODEPhysics::Collide) for the whole object: the union (OR) of its collisions' masks;
  /// `without_contact` when any of them collides without contact.
  std::uint32_t collide_bitmask = 0xffff;
  std::uint32_t without_contact_bitmask = 1;
  bool without_contact = false;
  const Surface& at(int index) const {
    return (index >= 0 && index < static_cast<int>(children.size())) ? children[index] : children[0];
  }
};

/// Clamps SurfaceParams into a Surface: mu, kd >= 0, kp <= 0 -> rigid; fdir1 normalised and
/// rotated into the collider frame by R_CL. Recovery: max_vel from the params or
/// default_max_vel, negative -> infinite; min_depth >= 0.
Surface toSurface(const SurfaceParams& p, const Eigen::Matrix3d& R_CL, double default_max_vel);

/// How the normal row of one contact behaves: everything but the time step and the world's cap.
struct ContactLaw {
  bool soft = false;          // kp/kd below are used; else a rigid contact (the solver's erp2)
  double kp = 0.0, kd = 0.0;  // with the tyre, if any
  double max_vel = std::numeric_limits<double>::infinity();  // the bodies' (m/s)
  double min_depth = 0.0;                                     // depth left uncorrected (m)
};

/// Springs in series, dampers in parallel (ODE):
///   kp = 1 / (1/kp_0 + 1/kp_1),  kd = kd_0 + kd_1,
/// and when exactly one side is a wheel with a tyre k_t, c_t:
///   kp = 1 / (1/kp + 1/k_t),  kd = kd + c_t.
/// soft = kp < kRigidKp / 2. max_vel and min_depth: the smaller of the two body sides' (a static
/// side does not count; none: infinite and 0).
ContactLaw contactLaw(const ColliderSurfaces& c0, const Surface& s0, const ColliderSurfaces& c1,
                      const Surface& s1);

/// ODE's ERP and CFM of a soft contact: erp = dt kp / (dt kp + kd), cfm = 1 / (dt kp + kd)
/// (as Bullet's multibody solver derives them from stiffness and damping).
struct ErpCfm {
  double erp = 0.0, cfm = 0.0;
};
ErpCfm softErpCfm(double kp, double kd, double dt);

/// Penetration recovery: a contact `depth` deep (> 0) is pushed apart at
///   c = min(erp max(depth - min_depth, 0), cap dt) / dt,  cap = min(law.max_vel, world_cap).
/// Returns the per-point ERP erp' = c dt / depth when that differs from plain `erp` (min_depth
/// > 0 or the cap binds), else nothing.
std::optional<double> cappedErp(const ContactLaw& law, double erp, double depth, double dt,
                                double world_cap);

/// The friction coefficient of the contact's cone: the larger of ODE's per-direction minima,
/// max(min(mu1_0, mu1_1), min(mu2_0, mu2_1)); the collider's anisotropy shrinks the other one.
double combinedFriction(const Surface& s0, const Surface& s1);

}  // namespace tianracer_sim

#endif  // TIANRACER_SIM_PHYSICS_CONTACT_LAW_H
