#pragma once
// The Schur complement of the direct accelerations along the structure of A (internal header;
// docs/performance.md "One evaluation of the double four-bar"). Eq. 4.1 with M^-1 constant:
//   N   = unit-row scaling of A D (D = col_scale)                   (row_scale, m1)
//   P   = N A M^-1                                                   (m1 x n1)
//   G   = P (N A)^T = N A M^-1 A^T N  (lower triangle, Cholesky L L^T)
//   G lambda_n = P rhs - N c,   a = M^-1 rhs - P^T lambda_n,   lambda = N lambda_n
// A row of A has 2 to 6 entries and M^-1 couples only the variables of one body (and of the
// bodies that share a node), so P and G have few entries. Their patterns are fixed by the model:
// analyse() lists, once, the products that make each entry of P and of G (scatter lists over the
// pattern of A and the nonzeros of the constant M^-1), and an evaluation runs those lists, a
// dense Cholesky of G (m1 small: the dense path) and sparse triangular products. No allocation
// after analyse(). The arithmetic differs from the dense GEMMs only in the order of the sums.
#include <Eigen/Core>
#include <vector>

namespace mo2d::detail {

class StructuredSchur {
 public:
  // rows[i]: the columns of the (structural) entries of row i of A; Minv: the constant M^-1.
  void analyse(const std::vector<std::vector<int>>& rows, const Eigen::MatrixXd& Minv);
  bool analysed() const { return !row_ptr_.empty(); }
  // Every nonzero of A lies in the pattern (else: grow() before factor()). Reads all of A: the
  // forward path checks each entry as it is written instead (in_pattern).
  bool covers(const Eigen::MatrixXd& A) const;
  // (row, col) is an entry of the pattern analysed (O(1): a table of m1 x n1 flags)
  bool in_pattern(int row, int col) const { return in_[row + static_cast<std::size_t>(col) * m_]; }
  // The pattern extended by the given entries of each row, analysed again (allocates; a model
  // whose rows gain entries with the state).
  void grow(const std::vector<std::vector<int>>& extra, const Eigen::MatrixXd& Minv);
  // N (into row_scale), P and the Cholesky of G. Returns (min/max of L's diagonal)^2, the
  // conditioning estimate of N A in the mass metric; 0 where G is not positive definite.
  double factor(const Eigen::MatrixXd& A, const Eigen::VectorXd& col_scale,
                Eigen::VectorXd& row_scale);
  // a and lambda from the last factor(); r (m1) is a work vector.
  void solve(const Eigen::VectorXd& rhs, const Eigen::VectorXd& c, const Eigen::VectorXd& row_scale,
             Eigen::VectorXd& r, Eigen::VectorXd& a, Eigen::VectorXd& lambda) const;

 private:
  int m_ = 0, n_ = 0;
  std::vector<std::vector<int>> rows_;  // the pattern analysed
  std::vector<int> row_ptr_, col_;      // A's pattern, compressed by rows
  std::vector<int> lin_;    // index of each entry of the pattern in A's column-major data
  std::vector<char> in_;    // in_[i + j m1]: (i, j) is in the pattern
  std::vector<double> an_;  // N A along the pattern
  // M^-1 by rows (symmetric): its nonzeros
  std::vector<int> minv_ptr_, minv_col_;
  std::vector<double> minv_val_;
  // P by rows: its pattern p_ptr_/p_col_, values p_; p_[p_at] += an_[a] * minv_val_[v]
  std::vector<int> p_ptr_, p_col_;
  std::vector<double> p_;
  struct PTerm {
    int p_at, a, v;
  };
  std::vector<PTerm> p_terms_;
  // G(i, j), j <= i, column-major m1 x m1: g_[g_at] += p_[p] * an_[a]
  struct GTerm {
    int g_at, p, a;
  };
  std::vector<GTerm> g_terms_;
  Eigen::MatrixXd L_;  // G, then its Cholesky factor (lower triangle)
  bool cholesky();
};

}  // namespace mo2d::detail
