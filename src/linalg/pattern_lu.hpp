#pragma once
// LU of a small sparse matrix (n ~ 10..40, rows of 2 to 6 entries) whose pattern and pivot order
// stay the same from one call to the next: the inverse-dynamics samples (K = [A; E] and the
// Newton Jacobian of the positions).
//
// Analysis (first call, and whenever the check below fails): the dense partial-pivoting LU of
// SmallLU gives the pivot order (its row transpositions); the pattern of the nonzeros of A (the
// union over all analyses) is eliminated symbolically in that order, giving the pattern of L and
// U with their fill. Later calls refactor numerically along the fixed order, touching only the
// entries of that pattern, and the triangular solves visit only the nonzeros of L and U.
//
// Safety. A refactorization is used only if it is the one partial pivoting would compute:
//   - every multiplier satisfies |l_ik| <= 1 (the fixed pivot is a largest entry of its column,
//     i.e. partial pivoting would choose it too, up to ties);
//   - A has no nonzero outside the analysed pattern;
//   - no pivot is zero, and min|U_ii| / max|U_ii| >= dense_below (near a singular matrix the
//     caller's thresholds see exactly the dense factorization's pivot ratio).
// Otherwise this call factors densely (SmallLU, the previous path, same results) and, unless
// only the last test failed, the next call is analysed afresh from the current values.
// Storage is allocated by the constructor and the analyses; compute and the solves allocate
// nothing.
#include <Eigen/Core>
#include <cstdint>
#include <vector>

#include "linalg/small_lu.hpp"

namespace mo2d::detail {

class PatternLU {
 public:
  // dense_below: pivot ratio under which a call factors densely (see above)
  explicit PatternLU(int n, double dense_below = 0);

  // Factor diag(r) A diag(c) (r, c: row and column scaling; empty: ones). Returns
  // min|U_ii| / max|U_ii| (0 if singular), as SmallLU::compute.
  double compute(const Eigen::Ref<const Eigen::MatrixXd>& A);
  double compute_scaled(const Eigen::Ref<const Eigen::MatrixXd>& A, const Eigen::VectorXd& r,
                        const Eigen::VectorXd& c);
  double pivot_ratio() const { return ratio_; }
  int det_sign() const;                                      // sign of det (+1, -1; 0 if singular)
  void solve_in_place(Eigen::Ref<Eigen::VectorXd> x) const;  // x = A^-1 x
  void solve_transpose_in_place(Eigen::Ref<Eigen::VectorXd> x) const;  // x = A^-T x

  // counters (tests, benchmarks): analyses, sparse refactorizations, dense factorizations
  long analyses = 0, refactorizations = 0, dense_factorizations = 0;
  bool last_sparse() const { return sparse_; }  // whether the last compute used the pattern

 private:
  bool outside_pattern(const Eigen::Ref<const Eigen::MatrixXd>& A) const;
  bool refactor();  // numeric LU of w_ along the fixed order; false if a pivot test fails
  void analyse(const Eigen::Ref<const Eigen::MatrixXd>& A);

  int n_;
  double dense_below_;
  SmallLU dense_;
  Eigen::MatrixXd scaled_;                       // the scaled matrix (dense path)
  Eigen::MatrixXd w_;                            // L and U in place (zero outside their pattern)
  std::vector<uint64_t> outside_;                // all ones where A's pattern has no entry
  Eigen::MatrixXd outside_mask_;                 // 1 there, 0 on the pattern (outside_pattern)
  std::vector<char> lu_pattern_;                 // pattern of L + U (rows in pivot order)
  std::vector<int> row_at_, pos_;                // pivot position -> row of A, and back
  std::vector<int> swap_;                        // row transpositions (as SmallLU's)
  std::vector<int> swapped_;                     // the k with swap_[k] != k, in order
  std::vector<int> src_, dst_, row_, col_;       // A's entries: index in A, in w_, row, column
  std::vector<int> fill_;                        // index in w_ of the fill entries (reset to 0)
  std::vector<int> l_start_, l_row_, l_idx_;     // column k of L: rows, index in w_
  std::vector<int> u_start_, u_col_;             // row k of U (right of the diagonal): columns
  std::vector<int> uc_start_, uc_row_, uc_idx_;  // column j of U (above the diagonal)
  int perm_sign_ = 1;
  bool analysed_ = false, sparse_ = false;
  double ratio_ = 0;
};

}  // namespace mo2d::detail
