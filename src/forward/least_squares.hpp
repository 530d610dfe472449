#pragma once
// The least-squares multipliers of the reactions (internal header), shared by the dense path
// (forward_reactions.cpp) and the sparse engine (sparse_engine.cpp): lambda minimizing
// |A^T lambda - x| with the smallest norm where A loses rank, from the Cholesky factor of the
// regularized normal matrix G = A A^T + eps max(1, max diag) I, refined on the true residual.
//
// The normal equations alone lose the square of the conditioning: the regularization and the
// rounding of G perturb lambda by ~1e-16 kappa(A)^2 (the forward reactions of the shipped scenes
// were ~1e-8 N off at exact states, issue 30). Each refinement step, d = G^-1 A (x - A^T lambda),
// lambda += d, divides the error in a direction of singular value sigma by eps / (sigma^2 + eps)
// (~1e-8 for kappa(A) = 1e3): two or three steps reach the rounding of the residual, an error of
// ~1e-16 kappa(A), as a QR solve would. The corrections stay in the range of A, so where A loses
// rank the result is the minimum-norm solution (iterated Tikhonov in the directions where
// sigma^2 is below eps: the reactions there are not unique, and the recorder warns).
#include <Eigen/Core>
#include <algorithm>

namespace mo2d::detail {

// Refinement steps at most (the first solve included); the loop ends when a correction, or the
// next one predicted from the last two, is below 1e-15 of lambda (|.|_inf): two solves where
// 1e-16 kappa(A)^2 is small, more as A nears a singular configuration.
inline constexpr int kLeastSquaresSteps = 5;

// lambda (m1) from x (n1); r (n1) and d (m1) are scratch; solve(v): v = G^-1 v in place. A: any
// matrix type with A * n1-vector and A^T * m1-vector products. No allocation.
template <class MatA, class Solve>
void refined_least_squares(const MatA& A, const Eigen::VectorXd& x, Solve&& solve,
                           Eigen::VectorXd& lambda, Eigen::VectorXd& r, Eigen::VectorXd& d) {
  lambda.setZero();
  r = x;
  double prev = 0;
  for (int it = 0; it < kLeastSquaresSteps; ++it) {
    d.noalias() = A * r;
    solve(d);
    lambda += d;
    // converged: the correction, or the next one predicted from the contraction (the ratio of
    // the last two), is below 1e-15 of lambda
    const double dn = d.lpNorm<Eigen::Infinity>(), ln = lambda.lpNorm<Eigen::Infinity>();
    if (dn <= 1e-15 * ln || (it > 0 && dn * (dn / prev) <= 1e-15 * ln)) return;
    prev = dn;
    r = x;
    r.noalias() -= A.transpose() * lambda;
  }
}

}  // namespace mo2d::detail
