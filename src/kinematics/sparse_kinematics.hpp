#pragma once
// The sparse counterparts of the kinematic set-up's dense linear algebra (internal header), for
// large mechanisms (issue 14; docs/performance.md "Scaling"): every constraint row touches a few
// variables, so the Jacobians of a chain have O(n) entries, and the rank checks, the assembly's
// Newton steps, the initial velocities and the conditioning of `mo2d info` are O(n) (or
// O(n log n)) on them instead of the dense O(n^3). Below `kSparseKinematics` the dense path stays
// (faster on small models, and its results, error messages included, are those of the tests).
//
//   rank      Eigen's SparseQR of B^T (B = the dimensionless Jacobian, unit rows), COLAMD
//             ordering, a column (a row of B) whose remaining norm falls below the threshold is
//             dependent (Heath's method: in exact arithmetic, the rows that depend on the rows
//             before them in the ordering, as the dense column-pivoted QR finds them in its order)
//   assembly  the minimum-norm step J dx = psi: J^T P = Q R, dx = Q R^-T P^T psi on the leading
//             rank rows (what the dense complete orthogonal decomposition gives)
//   velocities [A; E] q1 = [b; v] by KLU (the dense path: LU with partial pivoting); the pivot
//             ratio min|U_ii| / max|U_ii| is the singularity test of both
//   condition sigma_max and sigma_min of B: the extreme eigenvalues of the Gram matrix of the
//             shorter side (power iteration, and inverse iteration on its sparse LDL^T)
#include <Eigen/Core>
#include <Eigen/SparseCore>
#include <vector>

#include "mo2d/model.hpp"

namespace mo2d::detail {

using SparseRowsK = Eigen::SparseMatrix<double, Eigen::RowMajor>;

// Models with n1 + m1 at least this use the sparse kinematics. Not a measured crossover: set above
// the models of the existing tests (their results stay the dense path's); the dense set-up of
// the N-four-bar at N = 40 (n1 + m1 = 325) takes 19 ms, the sparse one at N = 100 10 ms
// (docs/performance.md "Scaling").
constexpr int kSparseKinematics = 400;
inline bool sparse_kinematics(const Model& m) {
  return m.n1 + m.m1 >= kSparseKinematics;
}

// psi and the position Jacobian over the columns colmap[k] >= 0 of coordinate k (null: all n0).
void sparse_position_jacobian(const Model& m, const Eigen::VectorXd& q0, double t,
                              const int* colmap, int cols, Eigen::VectorXd& psi, SparseRowsK& J);
// A and b of A q1 = b.
void sparse_velocity_jacobian(const Model& m, const Eigen::VectorXd& q0, double t, SparseRowsK& A,
                              Eigen::VectorXd& b);
// J diag(d) with unit rows (a zero row stays zero), in place.
void make_dimensionless(SparseRowsK& J, const Eigen::VectorXd& d);

// Rows of B that depend on the others (threshold on the remaining column norm of B^T).
std::vector<int> sparse_dependent_rows(const SparseRowsK& B, double threshold);

// The minimum-norm solution of J dx = psi (J m x n, rank by the threshold): false when the
// factorization fails.
bool sparse_minimum_norm_step(const SparseRowsK& J, const Eigen::VectorXd& psi, double threshold,
                              Eigen::VectorXd& dx);

// The assembly's Gauss-Newton on the sparse Jacobian (assemble.cpp's options on the dense path:
// minimum-norm steps at the rank threshold 1e-12 of the largest row, Armijo backtracking down to
// alpha = 1e-8, non-finite trials rejected, `max_iterations` with the last not tested), holding
// the coordinates with colmap[k] < 0 (nfree others). psi: at q on return.
enum class SparseNewton { converged, non_finite, stalled, max_iterations };
SparseNewton sparse_assembly_newton(const Model& m, double tolerance, double t,
                                    const std::vector<int>& colmap, int nfree, Eigen::VectorXd& q,
                                    Eigen::VectorXd& psi);

// Solve K x = rhs (K square, column-major) by KLU: the pivot ratio min|U_ii| / max|U_ii| (0 if
// singular); x unspecified below 1e-300.
double sparse_lu_solve(const Eigen::SparseMatrix<double>& K, const Eigen::VectorXd& rhs,
                       Eigen::VectorXd& x);

// Extreme singular values of B (unit rows) and its rank at a relative threshold.
struct SparseSingular {
  double sigma_max = 0, sigma_min = 0;
  int rank = 0;
};
SparseSingular sparse_extreme_singular_values(const SparseRowsK& B, double rank_threshold);

}  // namespace mo2d::detail
