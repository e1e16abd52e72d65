// Internal: Bullet's headers (with their warnings silenced) and Eigen <-> Bullet conversions.
#ifndef TIANRACER_SIM_PHYSICS_BULLET_H
#define TIANRACER_SIM_PHYSICS_BULLET_H

#include <algorithm>
#include <cmath>

#include <Eigen/Geometry>

// Bullet's headers trip -Wunused-parameter (and GImpact's btAABB -Wdeprecated-copy); keep our own warnings meaningful.
#pragma GCC diagnostic push
#pragma GCC diagnostic ignored "-Wunused-parameter"
#pragma GCC diagnostic ignored "-Wdeprecated-copy"
#include <btBulletDynamicsCommon.h>
#include <BulletDynamics/Featherstone/btMultiBody.h>
#include <BulletDynamics/Featherstone/btMultiBodyConstraintSolver.h>
#include <BulletDynamics/Featherstone/btMultiBodyDynamicsWorld.h>
#include <BulletDynamics/Featherstone/btMultiBodyJointLimitConstraint.h>
#include <BulletDynamics/Featherstone/btMultiBodyJointMotor.h>
#include <BulletDynamics/Featherstone/btMultiBodyLinkCollider.h>
#include <BulletCollision/Gimpact/btGImpactCollisionAlgorithm.h>
#include <BulletCollision/Gimpact/btGImpactShape.h>
#include <LinearMath/btConvexHullComputer.h>
#pragma GCC diagnostic pop

#ifndef BT_USE_DOUBLE_PRECISION
#error "tianracer_sim_physics needs double-precision Bullet (pkg-config bullet-float64)"
#endif

namespace tianracer_sim {

inline btVector3 toBt(const Eigen::Vector3d& v) { return btVector3(v.x(), v.y(), v.z()); }
inline Eigen::Vector3d toEigen(const btVector3& v) { return Eigen::Vector3d(v.x(), v.y(), v.z()); }

inline btTransform toBt(const Eigen::Isometry3d& X) {
  const Eigen::Matrix3d& R = X.linear();
  btMatrix3x3 basis(R(0, 0), R(0, 1), R(0, 2), R(1, 0), R(1, 1), R(1, 2), R(2, 0), R(2, 1),
                    R(2, 2));
  return btTransform(basis, toBt(Eigen::Vector3d(X.translation())));
}

inline Eigen::Isometry3d toEigen(const btTransform& t) {
  Eigen::Isometry3d X = Eigen::Isometry3d::Identity();
  const btMatrix3x3& B = t.getBasis();
  for (int r = 0; r < 3; ++r) {
    for (int c = 0; c < 3; ++c) X.linear()(r, c) = B[r][c];
  }
  X.translation() = toEigen(t.getOrigin());
  return X;
}

inline btQuaternion toBtQuat(const Eigen::Matrix3d& R) {
  const Eigen::Quaterniond q(R);
  return btQuaternion(q.x(), q.y(), q.z(), q.w());
}

/// Bullet's rule for a sleeping multibody (btMultiBodyDynamicsWorld: applyGravity /
/// solveConstraints' addForce, clearMultiBodyForces, predictMultiBodyTransforms): any of its
/// colliders, base or link, ISLAND_SLEEPING. Bullet adds gravity to, integrates and clears the
/// forces of only a multibody that is not.
inline bool multiBodyAsleep(const btMultiBody& mb) {
  const btCollisionObject* base = mb.getBaseCollider();
  if (base != nullptr && base->getActivationState() == ISLAND_SLEEPING) return true;
  for (int i = 0; i < mb.getNumLinks(); ++i) {
    const btCollisionObject* c = mb.getLink(i).m_collider;
    if (c != nullptr && c->getActivationState() == ISLAND_SLEEPING) return true;
  }
  return false;
}

/// A rotation taking +Y to `axis` (unit), for Bullet's Y-up cylinders: Eigen's
/// Quaternion::FromTwoVectors(UnitY, axis), the same operations, without the JacobiSVD it
/// instantiates for an axis within 1e-12 of -Y (14 s of every first build's compile:
/// docs/performance.md, First build, part two). There it turns about the normal of +Y and
/// `axis` (the null vector the SVD looks for), or about +Z for -Y itself, which is the SVD's
/// answer for -Y (test_physics_rotation_y_to.cpp compares the two).
inline Eigen::Matrix3d rotationYTo(const Eigen::Vector3d& axis) {
  const Eigen::Vector3d v0 = Eigen::Vector3d::UnitY();
  const Eigen::Vector3d v1 = axis.normalized();
  double c = v1.dot(v0);
  Eigen::Quaterniond q;
  if (c < -1.0 + Eigen::NumTraits<double>::dummy_precision()) {
    c = std::max(c, -1.0);
    const Eigen::Vector3d n = v0.cross(v1);
    const double len = n.norm();
    const Eigen::Vector3d unit_n = len > 0.0 ? Eigen::Vector3d(n / len) : Eigen::Vector3d::UnitZ();
    const double w2 = (1.0 + c) * 0.5;
    q.w() = std::sqrt(w2);
    q.vec() = unit_n * std::sqrt(1.0 - w2);
  } else {
    const double s = std::sqrt((1.0 + c) * 2.0);
    const double invs = 1.0 / s;
    q.vec() = v0.cross(v1) * invs;
    q.w() = s * 0.5;
  }
  return q.toRotationMatrix();
}

}  // namespace tianracer_sim

#endif  // TIANRACER_SIM_PHYSICS_BULLET_H
