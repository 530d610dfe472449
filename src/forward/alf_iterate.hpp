#pragma once
// The augmented-Lagrangian iteration of the accelerations (internal header), shared by the dense
// fallback (forward_data.cpp) and the sparse path (forward_sparse.cpp).
#include <Eigen/Core>
#include <algorithm>
#include <cmath>

#include "mo2d/forward_data.hpp"

namespace mo2d::detail {

// The augmented-Lagrangian iteration (Bayo and Garcia de Jalon) on the matrices of the dense or
// the sparse path (A, M; solve: x = H^-1 x with H = M + alpha A^T N^2 A factorized), in residual
// form, warm-started from the last accepted multipliers d.lambda: r1 = f + B u - M a - A^T lambda,
// r2 = c - A a; H da = r1 + alpha A^T N^2 r2, a += da, lambda -= alpha N^2 (c - A a). Written on
// the true residuals, the iteration also refines away the rounding of the (ill-conditioned) H
// solves. It stops when converged or when the residual no longer halves: there the penalty
// regularizes the constraint instead of enforcing it with unbounded multipliers (the caller flags
// the result as inaccurate, accel_ok = false, so that an explicit integrator can step over this
// instant). Returns the iterations; prev: the last relative residual.
template <class MatA, class MatM, class Solve>
int alf_iterate(const MatA& A, const MatM& M, Solve&& solve, ForwardData& d, double& prev) {
  const int m1 = d.m.m1;
  auto r2 = d.ap.head(m1);
  d.a.setZero();
  prev = INFINITY;
  int it = 0;
  // Both residuals are measured in dimensionless terms: the generalized forces as D r1 against
  // D (f + B u) and D A^T lambda, the constraint rows as N r2 against N c plus a tenth of the
  // accelerations D^-1 a (so that a state at rest, c = 0, is judged on the size of a).
  auto inf_scaled = [](const VectorXd& v, const VectorXd& sc, bool divide) {
    double x = 0;
    for (Eigen::Index k = 0; k < v.size(); ++k)
      x = std::max(x, std::abs(divide ? v[k] / sc[k] : v[k] * sc[k]));
    return x;
  };
  for (; it < 40; ++it) {
    d.tmp0 = d.rhs;
    d.tmp0.noalias() -= M * d.a;
    d.tmp1.noalias() = A.transpose() * d.lambda;
    d.tmp0 -= d.tmp1;  // r1
    r2 = d.c;
    r2.noalias() -= A * d.a;
    const double s1 =
        inf_scaled(d.rhs, d.col_scale, false) + inf_scaled(d.tmp1, d.col_scale, false);
    const double s2 =
        inf_scaled(d.c, d.row_scale, false) + 0.1 * inf_scaled(d.a, d.col_scale, true);
    const double e = std::max(inf_scaled(d.tmp0, d.col_scale, false) / (s1 + 1e-300),
                              inf_scaled(r2, d.row_scale, false) / (s2 + 1e-300));
    if (it > 0 && (e <= 1e-14 || e > 0.5 * prev)) break;
    prev = e;
    r2.array() *= d.row_scale.array().square();
    d.tmp0.noalias() += d.alpha * A.transpose() * r2;
    solve(d.tmp0);
    d.a += d.tmp0;
    r2 = d.c;
    r2.noalias() -= A * d.a;
    r2.array() *= d.row_scale.array().square();
    d.lambda.noalias() -= d.alpha * r2;
  }
  return it;
}

}  // namespace mo2d::detail
