// Viscous joint damping, applied implicitly so that it cannot diverge (issue 43).
#ifndef TIANRACER_SIM_SRC_PHYSICS_JOINT_DAMPER_H
#define TIANRACER_SIM_SRC_PHYSICS_JOINT_DAMPER_H

#include "bullet.h"

namespace tianracer_sim {

/// A soft velocity constraint on one revolute or prismatic joint: the damping torque
/// tau = -c qd_new acts on the joint's velocity at the end of the step (backward Euler), so
/// that for any c >= 0 the joint's velocity only decays. Applied explicitly,
/// tau = -c qd_old overshoots once h c / I_eff > 2 and doubles every step (damping 3 on a
/// wheel of 1e-3 kg m^2 at h = 1 ms threw a robot 46 m in 0.2 s).
///
/// The row is Bullet's joint motor row (target velocity 0, unbounded) with constraint force
/// mixing: for the row's effective mass 1/A (A = J M^-1 J^T, Bullet's 1 / m_jacDiagABInv),
/// the impulse solves  A lambda + qd + s lambda = 0  with  s = 1 / (h c), i.e.
///   lambda = -qd / (A + 1/(h c)),   qd_new = qd / (1 + h c A),
/// the implicit update v' = v / (1 + h c / I_eff) for an isolated joint, and the same
/// soft-constraint solve for coupled ones. This is what Gazebo's ODE joints do for
/// <implicit_spring_damper> (gazebo-classic gazebo/physics/ode/ODEJoint.cc,
/// ApplyImplicitStiffnessDamping): a joint stop at the current position with
/// ERP = h kp / (h kp + kd) and CFM = 1 / (h kp + kd), here with kp = 0.
class JointDamper : public btMultiBodyJointMotor {
 public:
  JointDamper(btMultiBody* body, int link) : btMultiBodyJointMotor(body, link, 0.0, SIMD_INFINITY) {}

  /// The damping coefficient c (N m s/rad or N s/m), > 0.
  void setDamping(double c) { damping_ = c; }

  void createConstraintRows(btMultiBodyConstraintArray& rows, btMultiBodyJacobianData& data,
                            const btContactSolverInfo& info) override;

 private:
  double damping_ = 0.0;
};

}  // namespace tianracer_sim

#endif  // TIANRACER_SIM_SRC_PHYSICS_JOINT_DAMPER_H
