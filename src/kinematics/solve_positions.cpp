// The Newton solver of the position constraints (solve_positions.hpp): one loop, three kinds of
// step, three line searches.
#include "kinematics/solve_positions.hpp"

#include <Eigen/QR>
#include <cmath>

#include "kinematics/conditioning.hpp"
#include "kinematics/residuals.hpp"
#include "linalg/pattern_lu.hpp"

namespace mo2d::detail {

namespace {

struct Solve {
  const Model& m;
  const NewtonOptions& o;
  NewtonBuffers& w;
  double t;
  const int* colmap;  // null: all coordinates free

  void evaluate(const VectorXd& q) { position_jacobian(m, q, t, colmap, w.psi, w.J); }

  // dx with J dx = psi (or its least-squares / regularized counterpart); false if J is singular
  bool step() {
    switch (o.step) {
      case NewtonStep::lu:
        if (w.pattern_lu) {
          if (w.pattern_lu->compute(w.J) < o.singular_pivot_ratio) return false;
          w.dx = w.psi;
          w.pattern_lu->solve_in_place(w.dx);
          return true;
        }
        if (w.lu->compute(w.J) < o.singular_pivot_ratio) return false;
        w.dx = w.psi;
        w.lu->solve_in_place(w.dx);
        return true;
      case NewtonStep::minimum_norm: {
        Eigen::CompleteOrthogonalDecomposition<MatrixXd> cod(w.J);
        // (set after the factorization, as assemble always did: it changes the rank the solve
        // uses, not the decomposition)
        cod.setThreshold(o.rank_threshold);
        w.dx = cod.solve(w.psi);
        return true;
      }
      case NewtonStep::damped: {
        unit_row_scale(w.J, *w.col_scale, *w.row_scale);
        w.J = w.row_scale->asDiagonal() * w.J;  // dimensionless rows
        w.psi.array() *= w.row_scale->array();
        *w.W = *w.metric;
        w.W->noalias() += o.penalty * w.J.transpose() * w.J;
        w.llt->compute(*w.W);
        w.dx.noalias() = o.penalty * w.J.transpose() * w.psi;
        w.llt->solveInPlace(w.dx);
        return true;
      }
    }
    return false;
  }

  // q_out = q - alpha dx on the free coordinates (q_out may be q)
  void move(const VectorXd& q, double alpha, VectorXd& q_out) const {
    if (&q_out != &q) q_out = q;
    for (int k = 0; k < m.n0; ++k) {
      const int c = colmap ? colmap[k] : k;
      if (c >= 0) q_out[k] -= alpha * w.dx[c];
    }
  }

  enum class Trial { accepted, stalled, non_finite };

  // Backtracking from the whole step, psi and J evaluated at each trial point (so, on acceptance,
  // at the new iterate q). err: |psi|_inf at q (updated on acceptance); norm2: |psi|_2 at q.
  Trial search(VectorXd& q, double& err, double norm2) {
    for (double alpha = 1; alpha >= o.min_alpha; alpha *= 0.5) {
      move(q, alpha, *w.q_trial);
      evaluate(*w.q_trial);
      const bool finite = w.psi.allFinite();
      if (!finite && o.non_finite == NonFinite::stop) return Trial::non_finite;
      bool accept;
      if (o.line_search == LineSearch::decrease) {
        const double e = w.psi.lpNorm<Eigen::Infinity>();
        accept = e < err;
        if (accept) err = e;
      } else {
        accept = finite && w.psi.norm() <= (1 - 1e-4 * alpha) * norm2;
        if (accept) err = w.psi.lpNorm<Eigen::Infinity>();
      }
      if (accept) {
        q.swap(*w.q_trial);
        return Trial::accepted;
      }
    }
    evaluate(q);  // psi and J of the last iterate (they hold the last trial's)
    return Trial::stalled;
  }

  // The step dx taken (whole, or by the line search) from q; psi and J, and err = |psi|_inf,
  // evaluated at the new q unless `evaluate_new` is false (the last iteration, not tested).
  Trial advance(VectorXd& q, double& err, double norm2, bool evaluate_new) {
    if (o.line_search != LineSearch::none) return search(q, err, norm2);
    move(q, 1.0, q);
    if (evaluate_new) {
      evaluate(q);
      err = w.psi.lpNorm<Eigen::Infinity>();
    }
    return Trial::accepted;
  }
};

}  // namespace

NewtonResult solve_positions(const Model& m, const NewtonOptions& o, NewtonBuffers& w, double t,
                             std::span<const int> colmap, VectorXd& q0) {
  NewtonResult r;
  if (m.m0 == 0) return r;
  Solve s{m, o, w, t, colmap.empty() ? nullptr : colmap.data()};
  s.evaluate(q0);
  if (o.non_finite != NonFinite::ignore && !w.psi.allFinite()) {
    r.status = NewtonStatus::non_finite;
    return r;
  }
  double err = w.psi.lpNorm<Eigen::Infinity>();
  for (;;) {
    r.residual = err;
    if (err <= o.tolerance) return r;
    if (++r.iterations > o.max_iterations) break;
    const double norm2 = o.line_search == LineSearch::armijo ? w.psi.norm() : 0.0;
    if (!s.step()) {
      r.status = NewtonStatus::singular;
      return r;
    }
    const bool last = r.iterations == o.max_iterations && !o.test_last;
    const Solve::Trial trial = s.advance(q0, err, norm2, !last);
    if (trial != Solve::Trial::accepted) {
      r.status = trial == Solve::Trial::stalled ? NewtonStatus::stalled : NewtonStatus::non_finite;
      return r;
    }
    if (last) break;
  }
  r.status = NewtonStatus::max_iterations;
  return r;
}

}  // namespace mo2d::detail
