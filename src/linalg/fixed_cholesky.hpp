#pragma once
// Eigen's simplicial sparse Cholesky (SimplicialLLT / SimplicialLDLT, AMD ordering) for a matrix
// whose pattern is fixed, without heap allocation after analyse(): Eigen's own factorize() copies
// the symmetric permutation P A P^T into a new matrix at every call (and permute_symm_to_symm
// allocates a counter), and its solve() applies P^-1 in place through a temporary mask. Here the
// permuted matrix is a member whose values are gathered through an index map found once, and
// solve_in_place() goes through a work vector. The arithmetic is Eigen's (factorize_preordered
// and the triangular solves), so the factors and the results are those of Eigen's calls.
// (factorize_preordered's own work arrays are on the stack up to Eigen's 128 kB limit: n up to
// 16,000 for the values, the largest array.)
#include <Eigen/SparseCholesky>
#include <Eigen/SparseCore>
#include <numeric>
#include <type_traits>
#include <vector>

namespace mo2d::detail {

template <class Base>  // Eigen::SimplicialLLT<SparseCols> or Eigen::SimplicialLDLT<SparseCols>
class FixedCholesky : public Base {
 public:
  using Matrix = Eigen::SparseMatrix<double>;

  // The ordering, the elimination tree and the gather map of the lower triangle of A (stored
  // lower, compressed). Allocates.
  void analyse(const Matrix& A) {
    this->analyzePattern(A);
    Matrix marks = A;  // the values 1 .. nnz mark where each entry of A lands in P A P^T
    std::iota(marks.valuePtr(), marks.valuePtr() + marks.nonZeros(), 1.0);
    permuted_.resize(A.rows(), A.cols());
    permuted_.template selfadjointView<Eigen::Upper>() =
        marks.template selfadjointView<Eigen::Lower>().twistedBy(this->m_P);
    gather_.resize(static_cast<std::size_t>(permuted_.nonZeros()));
    for (Eigen::Index k = 0; k < permuted_.nonZeros(); ++k)
      gather_[k] = static_cast<int>(permuted_.valuePtr()[k]) - 1;
    work_.resize(A.rows());
  }

  // Numerical factorization of A (the pattern given to analyse). No allocation.
  void factorize_fixed(const Matrix& A) {
    const double* a = A.valuePtr();
    double* p = permuted_.valuePtr();
    for (std::size_t k = 0; k < gather_.size(); ++k) p[k] = a[gather_[k]];
    this->template factorize_preordered<kLdlt>(permuted_);
  }

  // D of the LDL^T (Eigen's vectorD() returns a copy)
  const Eigen::VectorXd& diagonal() const { return this->m_diag; }

  // x = A^-1 x with the last factors. No allocation.
  void solve_in_place(Eigen::VectorXd& x) {
    work_.noalias() = this->m_P * x;
    this->matrixL().solveInPlace(work_);
    if constexpr (kLdlt) work_.array() *= this->m_diag.array().inverse();  // as Eigen's solve
    this->matrixU().solveInPlace(work_);
    x.noalias() = this->m_Pinv * work_;
  }

 private:
  static constexpr bool kLdlt =
      std::is_same_v<Base, Eigen::SimplicialLDLT<Matrix, Eigen::Lower, Eigen::AMDOrdering<int>>>;
  Matrix permuted_;          // P A P^T, upper triangle (Eigen's factorize_preordered input)
  std::vector<int> gather_;  // its values: permuted_[k] = A.values[gather_[k]]
  Eigen::VectorXd work_;
};

}  // namespace mo2d::detail
