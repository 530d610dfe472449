// The Jacobian of the accelerations (mo2d/jacobian.hpp): one directional derivative per state
// variable, all solved with one factorization of [M A^T; A 0] at the state.
//
// Per direction (dq0, dq1) = a unit vector e_k of the state (derivation at the top of
// mo2d/jacobian.hpp; the element derivatives in constraints/derivatives.hpp and
// dynamics/derivatives.cpp):
//   r1 = df + B du - dA^T lambda,  r2 = dc - dA a,  [M A^T; A 0] [da; dlambda] = [r1; r2]
// dA vanishes along q1 (A depends on q0 only). Joint friction (its value depends on the
// reactions, iterated per evaluation) is differenced: central differences of the whole
// evaluation, and J.approximate says so.
#include "mo2d/jacobian.hpp"

#include <Eigen/LU>
#include <Eigen/QR>
#include <algorithm>
#include <cmath>
#include <optional>

#include "constraints/derivatives.hpp"
#include "constraints/sinks.hpp"
#include "dynamics/derivatives.hpp"
#include "mo2d/dynamics.hpp"
#include "mo2d/error.hpp"

namespace mo2d {
namespace {

using Eigen::MatrixXd;
using Eigen::VectorXd;

// Central differences of the evaluation (step 1e-6 of the variable's scale).
void differenced(ForwardData& d, double t, const VectorXd& q0, const VectorXd& q1,
                 AccelerationJacobian& J) {
  const Model& m = d.m;
  VectorXd x0 = q0, x1 = q1, ap(m.n1);
  for (int k = 0; k < m.n0 + m.n1; ++k) {
    const bool pos = k < m.n0;
    double& x = pos ? x0[k] : x1[k - m.n0];
    const double x_at = x, h = 1e-6 * std::max(std::abs(x_at), pos ? m.scale : 1.0);
    x = x_at + h;
    d.accelerations(t, x0, x1, false);
    ap = d.a;
    x = x_at - h;
    d.accelerations(t, x0, x1, false);
    x = x_at;
    (pos ? J.da_dq0.col(k) : J.da_dq1.col(k - m.n0)) = (ap - d.a) / (2 * h);
  }
  d.accelerations(t, q0, q1, false);
}

// The right-hand side [r1; r2] of one direction (dq0, dq1) into col.
struct DirectionWork {
  VectorXd a, lambda;  // n1, m1: the accelerations and multipliers at the state
  VectorXd dlocal;     // slots: d body_applied
  VectorXd df, du;     // n1, nu: d f, d u
  VectorXd r1, dc;     // n1, m1: the two blocks of the right-hand side
  MatrixXd dA;         // m1 x n1: d A along dq0
};
bool direction_rhs(ForwardData& d, double t, const VectorXd& q0, const VectorXd& q1,
                   const VectorXd& dq0, const VectorXd& dq1, bool along_q0, DirectionWork& w,
                   Eigen::Ref<VectorXd> col) {
  const Model& m = d.m;
  detail::body_applied_derivative(m, q0, q1, dq0, dq1, t, w.dlocal);
  w.df.setZero();
  scatter_local(m, w.dlocal, w.df);
  for (int k = 0; k < m.n_inputs(); ++k)
    w.du[k] = detail::law_jet(m, d.effort_laws[k], q0, q1, dq0, dq1, t, "effort of input",
                              m.inputs[k].label)
                  .d;
  w.r1 = w.df;
  if (m.n_inputs() > 0) w.r1.noalias() += d.B * w.du;
  bool exact = true;
  for (const Constraint& c : m.constraints)
    detail::acceleration_rows_derivative(m, c, q0, q1, dq0, dq1, t, w.dc, exact);
  if (along_q0 && m.m1 > 0) {
    w.dA.setZero();
    detail::DenseVelSink sink{w.dA};
    for (const Constraint& c : m.constraints)
      detail::velocity_rows_derivative(m, c, q0, dq0, t, sink);
    w.r1.noalias() -= w.dA.transpose() * w.lambda;
    w.dc.noalias() -= w.dA * w.a;
  }
  col.head(m.n1) = w.r1;
  col.tail(m.m1) = w.dc;
  return exact;
}

}  // namespace

void acceleration_jacobian(ForwardData& d, double t, const VectorXd& q0, const VectorXd& q1,
                           AccelerationJacobian& J) {
  if (d.sparse_engine())
    throw Error("acceleration_jacobian of '" + d.m.name +
                    "': the workspace uses sparse linear algebra; build it with "
                    "ForwardOptions::linear_algebra = dense",
                d.m.name, t);
  const Model& m = d.m;
  J.da_dq0.resize(m.n1, m.n0);
  J.da_dq1.resize(m.n1, m.n1);
  J.approximate.clear();
  J.singular = false;
  if (!m.frictions.empty()) {
    differenced(d, t, q0, q1, J);
    J.approximate = "joint friction: central differences of the whole evaluation";
    return;
  }
  d.accelerations(t, q0, q1, false);
  const int n = m.n0 + m.n1, nk = m.n1 + m.m1;
  MatrixXd K = MatrixXd::Zero(nk, nk);
  K.topLeftCorner(m.n1, m.n1) = d.M;
  K.topRightCorner(m.n1, m.m1) = d.A.transpose();
  K.bottomLeftCorner(m.m1, m.n1) = d.A;
  Eigen::PartialPivLU<MatrixXd> lu(K);
  // a singular configuration (dependent rows): minimum-norm solutions instead
  const bool regular = lu.rcond() > 1e-14;
  std::optional<Eigen::CompleteOrthogonalDecomposition<MatrixXd>> cod;
  if (!regular) cod.emplace(K);
  auto solve = [&](const MatrixXd& rhs) -> MatrixXd {
    if (regular) return lu.solve(rhs);
    return cod->solve(rhs);
  };
  // the multipliers at the state from the same system (the null-space formulation has none)
  VectorXd base(nk);
  base << d.rhs, d.c;
  base = solve(base);
  DirectionWork w{base.head(m.n1), base.tail(m.m1),        VectorXd(m.n_slots),
                  VectorXd(m.n1),  VectorXd(m.n_inputs()), VectorXd(m.n1),
                  VectorXd(m.m1),  MatrixXd(m.m1, m.n1)};
  MatrixXd R(nk, n);
  VectorXd dq0 = VectorXd::Zero(m.n0), dq1 = VectorXd::Zero(m.n1);
  bool exact = true;
  for (int k = 0; k < n; ++k) {
    const bool along_q0 = k < m.n0;
    (along_q0 ? dq0[k] : dq1[k - m.n0]) = 1;
    exact = direction_rhs(d, t, q0, q1, dq0, dq1, along_q0, w, R.col(k)) && exact;
    (along_q0 ? dq0[k] : dq1[k - m.n0]) = 0;
  }
  const MatrixXd X = solve(R);
  J.singular = !regular;
  if (!regular) J.approximate = "the constraint rows are dependent here: minimum-norm derivatives";
  J.da_dq0 = X.topLeftCorner(m.n1, m.n0);
  J.da_dq1 = X.topRightCorner(m.n1, m.n1);
  if (!exact && J.approximate.empty())
    J.approximate =
        "user position constraints: their curvature term's derivative in positions is a central "
        "difference (it needs third derivatives)";
}

}  // namespace mo2d
