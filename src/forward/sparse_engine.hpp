#pragma once
// The sparse linear algebra of forward dynamics (ForwardOptions::linear_algebra, internal header;
// docs/performance.md "Sparse engine"). In a mechanism every constraint row touches a few
// variables and the mass matrix couples the variables of one body and the nodes bodies share, so
// the matrices of one evaluation have O(n) entries. Their patterns are fixed by the model: they
// are found once (the first fill inserts the entries, later fills only rewrite values), the
// products below are scatter lists computed once, and the Cholesky factorizations analyse their
// pattern once (AMD ordering) and refactorize numerically per evaluation. Cost and memory linear
// in the size of a chain; no allocation after the first evaluation.
//
//   A     m1 x n1   velocity rows A q1 = b (row-major)
//   Psi   m0 x n0   position rows (the projection, the drift check)
//   M     n1 x n1   mass matrix (constant, eq. 5.25-5.27); M0 n0 x n0 the projection metric
//   H     n1 x n1   M + alpha A^T N^2 A: the augmented-Lagrangian matrix of the accelerations
//                   (Bayo and Garcia de Jalon; iterated as the dense fallback does) and of the
//                   velocity projection; N = unit-row scaling of A diag(d)
//   W0    n0 x n0   M0 + alpha Psi^T P^2 Psi: the position projection (the damped Newton step of
//                   solve_positions.hpp)
//   KKT   (n1 + m1)^2  [M (N A)^T; N A 0]: the direct solve of the accelerations away from
//                   singular configurations (SuiteSparse KLU: pivots chosen once, refactorized
//                   with them while they stay good, linalg/klu_lu.hpp), as the dense path solves
//                   directly there
//   G     m1 x m1   N A D^2 A^T N (D = diag(d)): its LDL^T pivots give the conditioning estimate
//                   min(D) / max(D) (the dense path's pivot ratio of the same Gram matrix); and
//                   A A^T + eps I, the least-squares multipliers of the reactions
// Only the lower triangles of H, W0 and G are stored (what SimplicialLLT/LDLT read).
#include <Eigen/Core>
#include <Eigen/SparseCholesky>
#include <Eigen/SparseCore>
#include <vector>

#include "dynamics/reactions.hpp"
#include "linalg/fixed_cholesky.hpp"
#include "linalg/klu_lu.hpp"
#include "mo2d/model.hpp"

namespace mo2d::detail {

using SparseRows = Eigen::SparseMatrix<double, Eigen::RowMajor>;
using SparseCols = Eigen::SparseMatrix<double, Eigen::ColMajor>;

// C = base + sum over the rows i of J of w_i J_i^T J_i (lower triangle): the pattern and the
// scatter of every product of two entries of a row, computed once per pattern of J.
struct RowProduct {
  SparseCols C;
  std::vector<int> base_at;  // per entry of base: its index in C's values
  struct Pair {
    int at, a, b, row;  // C.values[at] += w[row] * J.values[a] * J.values[b]
  };
  std::vector<Pair> pairs;
  void build(const SparseRows& J, const SparseCols& base);
  void fill(const SparseRows& J, const SparseCols& base, const Eigen::VectorXd& w, double scale);
};

// C = sum over the columns j of J of w_j (s J)_j (s J)_j^T (lower triangle, m x m), s a row
// scaling: the Gram matrix of the rows.
struct ColumnProduct {
  SparseCols C;
  std::vector<int> diag_at;  // index of C(i, i) in C's values
  struct Pair {
    int at, a, b, col, ra, rb;  // C.values[at] += w[col] s[ra] J.values[a] s[rb] J.values[b]
  };
  std::vector<Pair> pairs;
  void build(const SparseRows& J);
  void fill(const SparseRows& J, const Eigen::VectorXd& w, const Eigen::VectorXd& s);
};

class SparseEngine {
 public:
  // M, and M0 with the dense path's floor (1e-6 of the mass scale in dimensionless terms)
  SparseEngine(const Model& m, const Eigen::VectorXd& col_scale);

  SparseRows A, Psi;      // the current constraint rows (values of the last fill)
  SparseCols M, M0;       // constant
  double mass_scale = 1;  // largest entry of the dimensionless D M D (1 without mass)

  // A and b at (q0, t); Psi and psi likewise.
  void fill_velocity(const Eigen::VectorXd& q0, double t, Eigen::VectorXd& b);
  void fill_position(const Eigen::VectorXd& q0, double t, Eigen::VectorXd& psi);
  // A and b, and the entries owned by body slots (reactions; src/dynamics/reactions.hpp).
  void fill_velocity_slots(const Eigen::VectorXd& q0, double t, Eigen::VectorXd& b,
                           std::vector<SlotEntry>& entries);
  // out_i = 1 / |row i of J diag(d)| (1 for a zero row)
  static void unit_row_scale(const SparseRows& J, const Eigen::VectorXd& d, Eigen::VectorXd& out);

  // H = M + alpha A^T N^2 A factorized; false if it is not positive definite.
  bool factor_H(double alpha, const Eigen::VectorXd& row_scale);
  // x = H^-1 x
  void solve_H(Eigen::VectorXd& x);
  // [M (N A)^T; N A 0] [a; lambda_n] = [rhs; N c] by sparse LU, lambda = N lambda_n; false when
  // the factorization fails or the result is not finite (a and lambda then unspecified).
  bool solve_kkt(const Eigen::VectorXd& rhs, const Eigen::VectorXd& c,
                 const Eigen::VectorXd& row_scale, Eigen::VectorXd& a, Eigen::VectorXd& lambda);
  // min(D) / max(D) of the LDL^T of N A D^2 A^T N (1 without rows): ~ (sigma_min / sigma_max)^2
  double conditioning(const Eigen::VectorXd& col_scale, const Eigen::VectorXd& row_scale);
  // the minimum-norm least-squares lambda of A^T lambda = x: (A A^T + eps max(1, max diag) I)^-1
  // A x refined on the residual (least_squares.hpp)
  void least_squares(const Eigen::VectorXd& x, double eps, Eigen::VectorXd& lambda);
  // Damped Newton on psi = 0 in the metric M0 (solve_positions.hpp's NewtonStep::damped, six
  // steps, the last not tested): q0 -= (M0 + alpha Psi^T P^2 Psi)^-1 alpha Psi^T P^2 psi.
  void project_positions(double t, Eigen::VectorXd& q0, double alpha,
                         const Eigen::VectorXd& pos_scale, double tol, Eigen::VectorXd& psi);

 private:
  const Model& m_;
  int version_A_ = -1, version_Psi_ = -1;  // pattern versions the products were built for
  int pattern_A_ = 0, pattern_Psi_ = 0;    // incremented when a fill inserts entries
  RowProduct H_, W0_;
  ColumnProduct G_, R_;  // conditioning Gram (scaled), reactions Gram (unscaled)
  // the KKT matrix: its pattern, the positions of M's entries and of each entry of A (in the
  // lower-left block and in the upper-right transpose)
  SparseCols kkt_;
  std::vector<int> kkt_M_at_, kkt_A_at_, kkt_At_at_;
  KluLU lu_kkt_;
  Eigen::VectorXd kkt_x_, kkt_b_, kkt_r_;
  void build_kkt();
  FixedCholesky<Eigen::SimplicialLLT<SparseCols>> llt_H_, llt_W0_, llt_R_;
  FixedCholesky<Eigen::SimplicialLDLT<SparseCols>> ldlt_G_;
  Eigen::VectorXd ones_m1_, ones_n1_, w_m_, tmp_n_, tmp_n0_, tmp_m_, pos_row_scale_, pos_rhs_, dq0_;
  bool analysed_H_ = false, analysed_W0_ = false, analysed_G_ = false, analysed_R_ = false;

  void refresh_A();
  void refresh_Psi();
};

}  // namespace mo2d::detail
