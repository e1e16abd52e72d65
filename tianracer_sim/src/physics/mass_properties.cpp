#include "tianracer_sim/physics/mass_properties.h"

#include <algorithm>
#include <cmath>

#include <Eigen/Eigenvalues>

namespace tianracer_sim {

MassProperties transformMassProperties(const MassProperties& m_B, const Eigen::Isometry3d& X_AB) {
  MassProperties m_A;
  m_A.mass = m_B.mass;
  m_A.com = X_AB * m_B.com;
  const Eigen::Matrix3d R = X_AB.linear();
  m_A.inertia = R * m_B.inertia * R.transpose();
  return m_A;
}

namespace {
Eigen::Matrix3d parallelAxis(double m, const Eigen::Vector3d& d) {
  return m * (d.squaredNorm() * Eigen::Matrix3d::Identity() - d * d.transpose());
}
}  // namespace

MassProperties combineMassProperties(const MassProperties& a, const MassProperties& b) {
  if (b.mass <= 0.0) return a;
  if (a.mass <= 0.0) return b;
  MassProperties c;
  c.mass = a.mass + b.mass;
  c.com = (a.mass * a.com + b.mass * b.com) / c.mass;
  c.inertia = a.inertia + parallelAxis(a.mass, a.com - c.com) + b.inertia +
              parallelAxis(b.mass, b.com - c.com);
  c.inertia = 0.5 * (c.inertia + c.inertia.transpose());
  return c;
}

PrincipalInertia principalInertia(const Eigen::Matrix3d& inertia) {
  PrincipalInertia p;
  const Eigen::Matrix3d I = 0.5 * (inertia + inertia.transpose());
  const double off = std::abs(I(0, 1)) + std::abs(I(0, 2)) + std::abs(I(1, 2));
  if (off <= 1e-14 * std::max(I.trace(), 1e-300)) {
    p.moments = I.diagonal();
    p.R.setIdentity();
    return p;
  }
  Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> solver(I);
  p.moments = solver.eigenvalues();
  p.R = solver.eigenvectors();
  if (p.R.determinant() < 0.0) p.R.col(2) = -p.R.col(2);  // a rotation, not a reflection
  return p;
}

bool isPositiveDefiniteInertia(const Eigen::Matrix3d& inertia) {
  if (!inertia.allFinite()) return false;
  const double scale = std::max(inertia.cwiseAbs().maxCoeff(), 1e-300);
  if ((inertia - inertia.transpose()).cwiseAbs().maxCoeff() > 1e-9 * scale) return false;
  return principalInertia(inertia).moments.minCoeff() > 0.0;
}

bool isPhysicalInertia(const Eigen::Matrix3d& inertia, double rel_tol) {
  if (!isPositiveDefiniteInertia(inertia)) return false;
  const Eigen::Vector3d m = principalInertia(inertia).moments;
  const double tol = rel_tol * m.sum();
  return m(0) + m(1) >= m(2) - tol && m(1) + m(2) >= m(0) - tol && m(0) + m(2) >= m(1) - tol;
}

}  // namespace tianracer_sim
