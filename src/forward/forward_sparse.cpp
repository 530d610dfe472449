// Forward dynamics on the sparse path (ForwardOptions::linear_algebra; the matrices and
// factorizations: sparse_engine.hpp): the workspace's set-up, the accelerations, the projection,
// and the pieces the recorder and the integrators read on either path.
#include <algorithm>
#include <cmath>
#include <memory>
#include <string>
#include <vector>

#include "constraints/constraints.hpp"
#include "dynamics/reactions.hpp"
#include "forward/alf_iterate.hpp"
#include "forward/sparse_engine.hpp"
#include "linalg/structured_schur.hpp"
#include "mo2d/dynamics.hpp"
#include "mo2d/error.hpp"
#include "mo2d/forward_data.hpp"
#include "mo2d/kinematics.hpp"
#include "run/format.hpp"

namespace mo2d {

using detail::fmt;

namespace {

// Records the columns of the entries of each velocity row (their values are ignored): A's pattern.
struct PatternSink {
  std::vector<std::vector<int>>& rows;
  void add(int row, const VarRef& ref, double /*value*/) {
    if (ref.var >= 0) rows[row].push_back(ref.var);
  }
};

// The pattern of A at (q0, t): the entries the constraints write there, whatever their values
// (fixed by the constraints' kinds and variables; a state may add one: SchurSink).
std::vector<std::vector<int>> velocity_pattern(const Model& m, const VectorXd& q0, double t) {
  std::vector<std::vector<int>> rows(m.m1);
  PatternSink sink{rows};
  VectorXd rhs = VectorXd::Zero(m.m1);
  for (const auto& c : m.constraints) detail::velocity_rows(m, c, q0, t, rhs, sink);
  return rows;
}

// Writes A as DenseVelSink does and notes an entry outside the structured Schur's pattern, so
// that the pattern check costs one table look-up per entry written, not a pass over all of A.
struct SchurSink {
  MatrixXd& A;
  const detail::StructuredSchur& schur;
  bool outside = false;
  void add(int row, const VarRef& ref, double v) {
    if (ref.var < 0) return;
    A(row, ref.var) += v;
    outside = outside || !schur.in_pattern(row, ref.var);
  }
};

}  // namespace

// The sparse path (sparse_engine.hpp): M and the products as sparse matrices in the engine; the
// dense matrices stay empty (the vectors: init_vectors).
void ForwardData::init_sparse() {
  sparse_ = std::make_unique<detail::SparseEngine>(m, col_scale);
  alpha = o.penalty > 0 ? o.penalty : 1e7 * sparse_->mass_scale;
}

bool uses_sparse(const Model& m, const ForwardOptions& o) {
  const bool can = o.formulation == Formulation::augmented_lagrangian &&
                   (o.integrator == Integrator::rk4 || o.integrator == Integrator::dopri5 ||
                    o.integrator == Integrator::erk6 || o.integrator == Integrator::erk8 ||
                    o.integrator == Integrator::baumgarte);
  switch (o.linear_algebra) {
    case LinearAlgebra::dense:
      return false;
    case LinearAlgebra::sparse:
      if (!can)
        throw Error(
            std::string("forward dynamics: linear_algebra sparse needs the augmented "
                        "Lagrangian formulation and rk4, dopri5, erk6, erk8 or baumgarte (got ") +
                to_string(o.formulation) + ", " + to_string(o.integrator) +
                "): CVODE's Newton matrix, the Lagrange and the null-space "
                "formulations are dense",
            "linear_algebra");
      return true;
    case LinearAlgebra::automatic:
      return can && m.n1 + m.m1 >= kSparseCrossover;
  }
  return false;
}

// The sparse path (sparse_engine.hpp), as the dense one: away from singular configurations (the
// conditioning estimate of N A D at least kDirectAccept) the direct solve of the KKT system by
// sparse LU; near one the augmented-Lagrangian iteration on the sparse H, which regularizes the
// degenerate direction. (The iteration alone is not exact enough: it cannot resolve the
// multipliers below about alpha eps / mass scale ~ 1e-9 relative.)
void ForwardData::solve_sparse(double t, const VectorXd& q0) {
  detail::SparseEngine& sp = *sparse_;
  detail::SparseEngine::unit_row_scale(sp.A, col_scale, row_scale);
  const double ratio = note_conditioning(t, q0, sp.conditioning(col_scale, row_scale));
  ++stats.factorizations;
  if (ratio >= kDirectAccept && sp.solve_kkt(rhs, c, row_scale, a, lambda)) return;
  if (!sp.factor_H(alpha, row_scale))
    throw Error("forward dynamics of '" + m.name +
                    "': the mass matrix is not positive on the mechanism's motions at t = " +
                    fmt(t) + " (a body without mass or inertia?)",
                m.name, t);
  if (!lambda.allFinite()) lambda.setZero();
  double prev = INFINITY;
  const int it = detail::alf_iterate(
      sp.A, sp.M, [&sp](VectorXd& x) { sp.solve_H(x); }, *this, prev);
  stats.solver_iterations += it;
  accel_residual = prev;
  accel_ok = prev <= kAlfAccept;
  ++stats.regularized_evaluations;
  if (!lambda.allFinite()) lambda.setZero();
}

// The same projection on the sparse matrices: positions by sparse_engine.hpp's damped Newton,
// velocities by the H of the new positions.
void ForwardData::project_sparse(double t, VectorXd& q0, VectorXd& q1, double tol_pos,
                                 double tol_vel) {
  detail::SparseEngine& sp = *sparse_;
  sp.project_positions(t, q0, alpha, pos_scale, tol_pos, psi);
  if (m.m1 == 0) return;
  sp.fill_velocity(q0, t, b);
  bool factored = false;
  for (int it = 0; it < 6; ++it) {
    velocity_residual_into(q1, r1);
    if (r1.lpNorm<Eigen::Infinity>() <= tol_vel) break;
    if (!factored) {
      detail::SparseEngine::unit_row_scale(sp.A, col_scale, row_scale);
      sp.factor_H(alpha, row_scale);
      factored = true;
    }
    r1.array() *= row_scale.array().square();
    dq1.noalias() = -alpha * sp.A.transpose() * r1;
    sp.solve_H(dq1);
    q1 += dq1;
  }
}

// A and b at (t, q0) on the dense path with the structured Schur: an entry written outside its
// pattern grows the pattern by the entries written at this state (allocates, once per new entry).
void ForwardData::fill_velocity_schur(double t, const VectorXd& q0) {
  A.setZero();
  SchurSink sink{A, *schur_};
  for (const auto& k : m.constraints) detail::velocity_rows(m, k, q0, t, b, sink);
  if (sink.outside) schur_->grow(velocity_pattern(m, q0, t), Minv);
}

void ForwardData::fill_velocity_rows(double t, const VectorXd& q0) {
  if (sparse_)
    sparse_->fill_velocity(q0, t, b);
  else if (schur_)
    fill_velocity_schur(t, q0);
  else
    velocity_jacobian(m, q0, t, A, b);
}

void ForwardData::velocity_residual_into(const VectorXd& q1, VectorXd& out) const {
  if (sparse_)
    out.noalias() = sparse_->A * q1;
  else
    out.noalias() = A * q1;
  out -= b;
}

void ForwardData::fill_position_rows(double t, const VectorXd& q0) {
  if (sparse_) {
    sparse_->fill_position(q0, t, psi);
    detail::SparseEngine::unit_row_scale(sparse_->Psi, pos_scale, pos_row_scale);
  } else {
    position_jacobian(m, q0, t, psi, Psi);
    row_scale_of(Psi, pos_scale, pos_row_scale);
  }
}

void ForwardData::mass_times(const VectorXd& x, VectorXd& out) const {
  if (sparse_)
    out.noalias() = sparse_->M * x;
  else
    out.noalias() = M * x;
}

MatrixXd ForwardData::dense_velocity_rows(double t, const VectorXd& q0) const {
  MatrixXd J = MatrixXd::Zero(m.m1, m.n1);
  VectorXd rhs1(m.m1);
  velocity_jacobian(m, q0, t, J, rhs1);
  return J;
}

}  // namespace mo2d
