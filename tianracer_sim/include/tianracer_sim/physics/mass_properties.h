// Rigid-body mass properties and the algebra Gazebo/SDF applies when it merges links joined by
// fixed joints ("fixed joint reduction"). ROS-free, Bullet-free.
#ifndef TIANRACER_SIM_PHYSICS_MASS_PROPERTIES_H
#define TIANRACER_SIM_PHYSICS_MASS_PROPERTIES_H

#include <Eigen/Geometry>

namespace tianracer_sim {

/// Mass m, centre of mass p_FC and inertia I_C (about the COM, axes of F), all in one frame F.
struct MassProperties {
  double mass = 0.0;
  Eigen::Vector3d com = Eigen::Vector3d::Zero();
  Eigen::Matrix3d inertia = Eigen::Matrix3d::Zero();
};

/// Re-expresses mass properties given in frame B in frame A (X_AB = pose of B in A):
///   p_A = X_AB p_B,   I_A = R_AB I_B R_AB^T   (still about the COM).
MassProperties transformMassProperties(const MassProperties& m_B, const Eigen::Isometry3d& X_AB);

/// Sum of two bodies given in the same frame (parallel-axis theorem):
///   m = m1 + m2,  c = (m1 c1 + m2 c2) / m,
///   I = sum_k I_k + m_k ((d_k.d_k) 1 - d_k d_k^T),  d_k = c_k - c.
/// Massless inputs contribute nothing; two massless inputs give a massless result.
MassProperties combineMassProperties(const MassProperties& a, const MassProperties& b);

/// Principal axes: I = R diag(moments) R^T with R a rotation (det +1). An already diagonal
/// inertia keeps R = identity (no axis permutation), so simple models keep simple frames.
struct PrincipalInertia {
  Eigen::Vector3d moments = Eigen::Vector3d::Zero();
  Eigen::Matrix3d R = Eigen::Matrix3d::Identity();  // columns: principal axes in the input frame
};
PrincipalInertia principalInertia(const Eigen::Matrix3d& inertia);

/// True when the inertia is finite, symmetric and positive definite (what ODE's dMassCheck asks).
bool isPositiveDefiniteInertia(const Eigen::Matrix3d& inertia);
/// True when the inertia is symmetric positive definite and satisfies the triangle inequality
/// of principal moments (I_a + I_b >= I_c), with a relative tolerance.
bool isPhysicalInertia(const Eigen::Matrix3d& inertia, double rel_tol = 1e-9);

}  // namespace tianracer_sim

#endif  // TIANRACER_SIM_PHYSICS_MASS_PROPERTIES_H
