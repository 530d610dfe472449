#pragma once
// Derivatives of the forward dynamics with respect to the state (q0, q1): the Jacobian of the
// accelerations a1(t, q0, q1) of eq. 4.13, for implicit integrators (CVODE BDF's Newton matrix)
// and for linearization (Orsino Proposition 4.4).
//
// With [M A^T; A 0] [a; lambda] = [f + B u; c] at (t, q0, q1), a direction (dq0, dq1) of the state
// gives the derivatives (da, dlambda) of the same system (M is constant):
//   [M A^T; A 0] [da; dlambda] = [df + B du - dA^T lambda;  dc - dA a]
// with df, du, dA, dc the directional derivatives of the applied forces, the efforts (laws), the
// velocity rows and the acceleration right-hand side. Each is exact: node positions and
// velocities are linear in q0 and q1 in the nodal formulation, the laws are evaluated on Jets,
// the user constraints' mixed second derivatives come from their Jets by polarization. What is
// not exact is named in AccelerationJacobian::approximate.
#include <Eigen/Core>
#include <string>

#include "mo2d/forward_data.hpp"

namespace mo2d {

// The exact derivatives of the accelerations a1(t, q0, q1) of forward dynamics with respect to the
// state (docs/equations.md: [M A^T; A 0][da; dlambda] = [df + B du - dA^T lambda; dc - dA a]);
// CVODE BDF's Newton matrix and the linearization use it.
struct AccelerationJacobian {
  Eigen::MatrixXd da_dq0;   // n1 x n0: d a1 / d q0
  Eigen::MatrixXd da_dq1;   // n1 x n1: d a1 / d q1
  std::string approximate;  // empty when every entry is exact; else what was differenced, and why
  bool singular = false;    // the constraint rows are dependent at the state: minimum-norm values
};

// The Jacobian of the accelerations at (t, q0, q1) with the efforts of the workspace's laws
// (ForwardOptions::efforts). Evaluates the accelerations first (d.a, d.lambda are left at
// (t, q0, q1)). Throws mo2d::Error where the accelerations cannot be evaluated.
void acceleration_jacobian(ForwardData& d, double t, const Eigen::VectorXd& q0,
                           const Eigen::VectorXd& q1, AccelerationJacobian& J);

}  // namespace mo2d
