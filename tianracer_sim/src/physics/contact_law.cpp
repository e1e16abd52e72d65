#include "tianracer_sim/physics/contact_law.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <utility>

namespace tianracer_sim {

Surface toSurface(const SurfaceParams& p, const Eigen::Matrix3d& R_CL, double default_max_vel) {
  Surface s;
  // A negative mu means no limit: Gazebo's FrictionPyramid::SetMu stores GZ_FLT_MAX for it
  // (gazebo/physics/SurfaceParams.cc); Gazebo's library models (pr2_gripper, ragdoll) use -1.
  const auto mu = [](double m) {
    return m < 0.0 ? static_cast<double>(std::numeric_limits<float>::max()) : m;
  };
  s.mu1 = mu(p.mu1);
  s.mu2 = mu(p.mu2);
  s.kp = p.kp > 0.0 ? p.kp : kRigidKp;
  s.kd = std::max(0.0, p.kd);
  if (p.fdir1.allFinite() && p.fdir1.norm() > 1e-9) {
    s.has_fdir1 = true;
    s.fdir1_C = R_CL * p.fdir1.normalized();
  }
  s.max_vel = p.max_vel ? *p.max_vel : default_max_vel;
  s.min_depth = std::max(0.0, p.min_depth);
  if (!(s.max_vel >= 0.0)) s.max_vel = std::numeric_limits<double>::infinity();
  return s;
}

ContactLaw contactLaw(const ColliderSurfaces& c0, const Surface& s0, const ColliderSurfaces& c1,
                      const Surface& s1) {
  ContactLaw law;
  // A tyre sits on one side only: a wheel on a wheel is left to the surfaces.
  law.kp = 1.0 / (1.0 / s0.kp + 1.0 / s1.kp);
  law.kd = s0.kd + s1.kd;
  if (c0.wheel != c1.wheel) {
    const ColliderSurfaces& tyre = c0.wheel ? c0 : c1;
    if (tyre.tyre_stiffness > 0.0) {
      law.kp = 1.0 / (1.0 / law.kp + 1.0 / tyre.tyre_stiffness);
      law.kd += tyre.tyre_damping;
    }
  }
  law.soft = law.kp < 0.5 * kRigidKp || law.kd >= kDampedKd;
  bool first = true;
  for (const auto& side : {std::make_pair(&c0, &s0), std::make_pair(&c1, &s1)}) {
    if (!side.first->body) continue;
    law.max_vel = std::min(law.max_vel, side.second->max_vel);
    law.min_depth = first ? side.second->min_depth : std::min(law.min_depth, side.second->min_depth);
    first = false;
  }
  return law;
}

ErpCfm softErpCfm(double kp, double kd, double dt) {
  // As btMultiBodyConstraintSolver::setupMultiBodyContactConstraint.
  const double denom = std::max(dt * kp + kd, std::numeric_limits<double>::epsilon());
  ErpCfm r;
  r.cfm = 1.0 / denom;
  r.erp = dt * kp / denom;
  return r;
}

std::optional<double> cappedErp(const ContactLaw& law, double erp, double depth, double dt,
                                double world_cap) {
  const double cap = std::min(law.max_vel, world_cap);
  if (depth > 0.0 && (law.min_depth > 0.0 || erp * depth > cap * dt)) {
    return std::min(erp * std::max(depth - law.min_depth, 0.0), cap * dt) / depth;
  }
  return std::nullopt;
}

double combinedFriction(const Surface& s0, const Surface& s1) {
  return std::max(std::min(s0.mu1, s1.mu1), std::min(s0.mu2, s1.mu2));
}

}  // namespace tianracer_sim
