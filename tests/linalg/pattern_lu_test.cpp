// The fixed-pattern LU (src/linalg/pattern_lu.hpp) against the dense partial-pivoting SmallLU it
// stands in for: on random sparse matrices whose values drift (the pivot order stays, or has to
// change), whose pattern grows, and which become singular. Along the fixed order the sparse
// elimination performs the dense one's operations on the nonzeros, so the two agree to rounding
// (here 1e-12 relative); where the order fails it must analyse again, never return a worse
// factorization.
#include "linalg/pattern_lu.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <random>
#include <vector>

#include "linalg/small_lu.hpp"

namespace pattern_lu_test {

using Eigen::MatrixXd;
using Eigen::VectorXd;
using mo2d::detail::PatternLU;
using mo2d::detail::SmallLU;

// A random n x n matrix with 2 to 6 entries per row (one on a random column of a random
// permutation, so that it is structurally nonsingular).
MatrixXd random_sparse(int n, std::mt19937_64& g) {
  std::uniform_real_distribution<double> u(-1, 1);
  std::uniform_int_distribution<int> col(0, n - 1), count(1, 5);
  std::vector<int> perm(n);
  for (int k = 0; k < n; ++k) perm[k] = k;
  std::shuffle(perm.begin(), perm.end(), g);
  MatrixXd A = MatrixXd::Zero(n, n);
  for (int i = 0; i < n; ++i) {
    A(i, perm[i]) = u(g) + (u(g) > 0 ? 1 : -1);
    for (int e = count(g); e > 0; --e) A(i, col(g)) = u(g);
  }
  return A;
}

double rel(const VectorXd& a, const VectorXd& b) {
  return (a - b).lpNorm<Eigen::Infinity>() / std::max(b.lpNorm<Eigen::Infinity>(), 1e-300);
}

// Both factorizations of A: solves, transposed solves, pivot ratio and det sign agree.
void expect_agree(PatternLU& p, const MatrixXd& A, std::mt19937_64& g, const char* what) {
  const int n = static_cast<int>(A.rows());
  SmallLU d(n);
  const double rd = d.compute(A), rp = p.compute(A);
  EXPECT_NEAR(rp, rd, 1e-12 * rd) << what;
  EXPECT_EQ(p.det_sign(), d.det_sign()) << what;
  if (rd == 0) return;
  std::uniform_real_distribution<double> u(-1, 1);
  VectorXd b(n);
  for (int i = 0; i < n; ++i) b[i] = u(g);
  VectorXd xd = b, xp = b;
  d.solve_in_place(xd);
  p.solve_in_place(xp);
  EXPECT_LT(rel(xp, xd), 1e-12) << what;
  xd = b, xp = b;
  d.solve_transpose_in_place(xd);
  p.solve_transpose_in_place(xp);
  EXPECT_LT(rel(xp, xd), 1e-12) << what;
  // and the solve is one: A x = b (the dense LU could share a wrong permutation)
  xp = b;
  p.solve_in_place(xp);
  EXPECT_LT((A * xp - b).lpNorm<Eigen::Infinity>(),
            1e-10 * (A.cwiseAbs().rowwise().sum().maxCoeff() * xp.lpNorm<Eigen::Infinity>()))
      << what;
}

TEST(PatternLU, AgreesWithDenseAlongDriftingValues) {
  std::mt19937_64 g(14);
  long sparse = 0, calls = 0;
  for (int n : {1, 2, 5, 12, 22, 35}) {
    for (int trial = 0; trial < 20; ++trial) {
      const MatrixXd A0 = random_sparse(n, g);
      PatternLU p(n);
      for (int step = 0; step < 30; ++step) {  // the values drift, the pattern stays
        MatrixXd A = A0;
        for (int j = 0; j < n; ++j)
          for (int i = 0; i < n; ++i)
            if (A(i, j) != 0) A(i, j) *= 1 + 0.2 * std::sin(0.05 * step + i + 2 * j);
        expect_agree(p, A, g, "drift");
        sparse += p.last_sparse();
        ++calls;
      }
      EXPECT_GE(p.analyses, 1);
      EXPECT_EQ(p.refactorizations + p.dense_factorizations, 30);
    }
  }
  // most calls follow the fixed order (the drift changes the pivot choice only now and then)
  EXPECT_GT(sparse, calls * 3 / 4) << sparse << " of " << calls;
}

TEST(PatternLU, ChangedPivotOrderAnalysesAgain) {
  // column 0: row 0 dominates, then row 2 does; partial pivoting must follow
  MatrixXd A(3, 3);
  A << 4, 1, 0, 0, 2, 1, 1, 0, 3;
  PatternLU p(3);
  std::mt19937_64 g(1);
  expect_agree(p, A, g, "first");
  expect_agree(p, A, g, "same");
  EXPECT_TRUE(p.last_sparse());
  EXPECT_EQ(p.analyses, 1);
  A(2, 0) = 8;  // |l_20| = 2 > 1 under the fixed order
  expect_agree(p, A, g, "order changed");
  EXPECT_FALSE(p.last_sparse());
  EXPECT_EQ(p.analyses, 2);
  expect_agree(p, A, g, "new order");
  EXPECT_TRUE(p.last_sparse());
}

TEST(PatternLU, EntryOutsideThePatternAnalysesAgain) {
  MatrixXd A(4, 4);
  A << 2, 0, 0, 1, 0, 3, 0, 0, 1, 0, 2, 0, 0, 1, 0, 4;
  PatternLU p(4);
  std::mt19937_64 g(2);
  expect_agree(p, A, g, "first");
  expect_agree(p, A, g, "same");
  EXPECT_TRUE(p.last_sparse());
  A(1, 2) = 0.5;  // a new entry (and fill below it)
  expect_agree(p, A, g, "grown");
  EXPECT_FALSE(p.last_sparse());
  expect_agree(p, A, g, "grown, again");
  EXPECT_TRUE(p.last_sparse());
  A(1, 2) = 0;  // an entry of the pattern that is zero stays in it
  expect_agree(p, A, g, "zero in the pattern");
  EXPECT_TRUE(p.last_sparse());
  A(0, 1) = NAN;  // non-finite outside the pattern: the dense path sees it
  SmallLU d(4);
  EXPECT_EQ(p.compute(A), d.compute(A));
  EXPECT_FALSE(p.last_sparse());
}

TEST(PatternLU, SingularAndNearSingularAreTheDenseFactorization) {
  std::mt19937_64 g(3);
  const int n = 12;
  const MatrixXd A0 = random_sparse(n, g);
  PatternLU p(n, 1e-2);
  expect_agree(p, A0, g, "regular");
  expect_agree(p, A0, g, "regular");
  ASSERT_TRUE(p.last_sparse());
  // column 5 scaled towards 0: the pattern and the pivot order stay, the pivot ratio falls
  for (double eps : {1e-5, 1e-9, 1e-14, 0.0}) {
    MatrixXd A = A0;
    A.col(5) *= eps;
    SmallLU d(n);
    const double rd = d.compute(A);
    EXPECT_EQ(p.compute(A), rd) << eps;  // exactly the dense pivot ratio
    EXPECT_FALSE(p.last_sparse()) << eps;
    EXPECT_EQ(p.det_sign(), d.det_sign()) << eps;
  }
}

}  // namespace pattern_lu_test
