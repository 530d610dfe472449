#pragma once
// Sparse LU by SuiteSparse's KLU (Davis and Palamadai Natarajan 2010: block triangular form, AMD
// ordering of the blocks, partial pivoting), for matrices whose pattern is fixed and whose values
// change a little between calls (the KKT system of each evaluation of forward dynamics): the
// pattern is analysed once (klu_analyze); the first factorization chooses the pivots
// (klu_factor), the later ones reuse them (klu_refactor, several times faster) unless the pivots
// have become poor, i.e. the reciprocal pivot ratio (klu_rcond) fell below a thousandth of the
// last full factorization's, and then it pivots again.
#include <Eigen/Core>
#include <Eigen/SparseCore>

namespace mo2d::detail {

class KluLU {
 public:
  KluLU();
  ~KluLU();
  KluLU(const KluLU&) = delete;
  KluLU& operator=(const KluLU&) = delete;

  // Factorize A (square, compressed column-major). A new pattern needs reset() first. False when
  // the matrix is singular to working precision.
  bool factorize(const Eigen::SparseMatrix<double>& A);
  // A full factorization with new pivots (after a solve the caller found inaccurate).
  bool repivot(const Eigen::SparseMatrix<double>& A);
  // x = A^-1 x with the last factors.
  void solve(Eigen::VectorXd& x);
  // forget the pattern and the factors
  void reset();
  // min|U_ii| / max|U_ii| of the last factorization (klu_rcond; 0 before one)
  double pivot_ratio() const;
  long refactorizations = 0, full_factorizations = 0;  // counters (benchmarks, tests)

 private:
  struct Impl;
  Impl* p_;
};

}  // namespace mo2d::detail
