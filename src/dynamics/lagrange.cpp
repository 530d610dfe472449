// Inverse dynamics with Lagrange multipliers on the unreduced model (validation formulation).
#include <Eigen/LU>

#include "mo2d/dynamics.hpp"
#include "mo2d/error.hpp"
#include "mo2d/inverse.hpp"
#include "mo2d/kinematics.hpp"
#include "output/result_rows.hpp"
#include "output/trajectory_labels.hpp"
#include "run/cpu_time.hpp"

namespace mo2d {

Trajectory inverse_dynamics_lagrange(const Model& m, std::span<const Prescribed> prescribed,
                                     const InverseOptions& options) {
  if (m.reduction != Reduction::none)
    throw Error("inverse_dynamics_lagrange needs a model built with Reduction::none", m.name);
  if (!m.frictions.empty())
    throw Error("inverse_dynamics_lagrange: joint friction '" + m.frictions[0].name +
                    "' is not part of this validation formulation (use inverse_dynamics)",
                m.frictions[0].name);
  // kinematics (positions, velocities) from the same per-sample solver; dynamics solved here
  InverseData d(m, prescribed, options);
  const MatrixXd M = mass_matrix(m);
  const MatrixXd B = input_matrix(m);
  const int n1 = m.n1, m1 = m.m1, nu = m.n_inputs(), dof = m.dof;
  const int N = n1 + m1 + dof;
  MatrixXd L = MatrixXd::Zero(N, n1 + m1 + nu);
  VectorXd rhs(N), f(n1), c(m1), bb(m1);
  MatrixXd A(m1, n1);
  Trajectory r = detail::labelled_trajectory(m, RunKind::inverse);
  const int S = options.samples;
  r.time.resize(S);
  r.q0.resize(S, m.n0);
  r.q1.resize(S, n1);
  r.a1.resize(S, n1);
  r.efforts.resize(S, nu);
  r.reactions.resize(S, m.n_reactions());
  r.residuals.resize(S, 3);
  const double start = detail::cpu_seconds();
  for (int k = 0; k < S; ++k) {
    const double t = S == 1 ? options.t0 : options.t0 + (options.t1 - options.t0) * k / (S - 1);
    inverse_dynamics_sample(m, d, t);  // positions and velocities (its dynamics are not used)
    velocity_jacobian(m, d.q0, t, A, bb);
    acceleration_rhs(m, d.q0, d.q1, t, c);
    applied_forces(m, d.q0, d.q1, t, f);
    L.setZero();
    L.topLeftCorner(n1, n1) = M;
    L.block(0, n1, n1, m1) = A.transpose();
    L.block(0, n1 + m1, n1, nu) = -B;
    L.block(n1, 0, m1, n1) = A;
    for (int i = 0; i < dof; ++i) L(n1 + m1 + i, d.p_index[i]) = 1.0;
    rhs << f, c, d.s_ddot;
    Eigen::PartialPivLU<MatrixXd> lu(L);
    const VectorXd x = lu.solve(rhs);
    const VectorXd lambda = x.segment(n1, m1);
    r.time[k] = t;
    detail::set_row(r.q0, k, d.q0);
    detail::set_row(r.q1, k, d.q1);
    detail::set_row(r.a1, k, x.head(n1));
    detail::set_row(r.efforts, k, x.tail(nu));
    for (int j = 0; j < m.n_reactions(); ++j)
      r.reactions(k, j) = m.reactions[j].factor * lambda[m.reactions[j].row];
    r.residuals.row(k) << d.residual_position, (A * d.q1 - bb).lpNorm<Eigen::Infinity>(),
        (A * x.head(n1) - c).lpNorm<Eigen::Infinity>();
  }
  r.stats.cpu_seconds = detail::cpu_seconds() - start;
  return r;
}

}  // namespace mo2d
