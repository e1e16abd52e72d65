#include "joint_damper.h"

#include <cmath>

namespace tianracer_sim {

void JointDamper::createConstraintRows(btMultiBodyConstraintArray& rows,
                                       btMultiBodyJacobianData& data,
                                       const btContactSolverInfo& info) {
  const int first = rows.size();
  // The motor's row: velocity target 0, m_rhs = -qd D with D = 1 / A (relaxation 1).
  btMultiBodyJointMotor::createConstraintRows(rows, data, info);
  const double h = info.m_timeStep;
  if (!(damping_ > 0.0) || !(h > 0.0)) return;
  for (int k = first; k < rows.size(); ++k) {
    btMultiBodySolverConstraint& row = rows[k];
    const double D = row.m_jacDiagABInv;
    if (!(D > 0.0)) continue;  // no effective mass (Bullet's SIMD_EPSILON guard): leave the row
    const double s = 1.0 / (h * damping_);  // compliance
    if (!std::isfinite(s)) continue;          // damping too small to act in this step
    const double D_soft = 1.0 / (1.0 / D + s);
    row.m_rhs *= D_soft / D;
    row.m_jacDiagABInv = D_soft;
    row.m_cfm = s * D_soft;
    row.m_lowerLimit = -SIMD_INFINITY;
    row.m_upperLimit = SIMD_INFINITY;
  }
}

}  // namespace tianracer_sim
