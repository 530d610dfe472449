// The Schur complement along the pattern of A (src/linalg/structured_schur.hpp) against the dense
// Schur solve it replaced in ForwardData::solve_schur (Eigen GEMMs and a dense LLT of
// N A M^-1 A^T N, copied below): the same equations summed in another order, so they must agree
// to rounding. On the accelerations of the shipped mechanisms, the N-four-bar and the generated
// mechanisms with a definite M (tests/metamorphic/generator.hpp), and on random patterns with a
// block-diagonal M^-1, including a pattern that has to grow.
#include "linalg/structured_schur.hpp"

#include <gtest/gtest.h>

#include <Eigen/Cholesky>
#include <Eigen/Eigenvalues>
#include <algorithm>
#include <cmath>
#include <vector>

#include "../../bench/n_fourbar.hpp"
#include "kinematics/conditioning.hpp"
#include "metamorphic/generator.hpp"
#include "mo2d/forward_data.hpp"
#include "mo2d/mechanisms.hpp"
#include "mo2d/model.hpp"

namespace mo2d {
namespace {

using Eigen::MatrixXd;
using Eigen::VectorXd;

struct DenseSchur {
  double ratio = 0;
  VectorXd a, lambda, row_scale;
};

// The dense solve of ForwardData::solve_schur before the structured one (verbatim arithmetic).
DenseSchur dense_schur(const MatrixXd& A, const MatrixXd& Minv, const VectorXd& col_scale,
                       const VectorXd& rhs, const VectorXd& c) {
  DenseSchur s;
  s.row_scale.resize(A.rows());
  detail::unit_row_scale(A, col_scale, s.row_scale);
  const MatrixXd An = s.row_scale.asDiagonal() * A;
  const MatrixXd AMinv = An * Minv;
  const MatrixXd G1 = AMinv * An.transpose();
  const Eigen::LLT<MatrixXd> llt(G1);
  const auto d = llt.matrixLLT().diagonal();
  const double dmax = d.maxCoeff(), dmin = d.minCoeff();
  s.ratio = (llt.info() == Eigen::Success && dmax > 0) ? (dmin / dmax) * (dmin / dmax) : 0;
  VectorXd r1 = -c.cwiseProduct(s.row_scale) + AMinv * rhs;
  llt.solveInPlace(r1);
  s.a = Minv * rhs - AMinv.transpose() * r1;
  s.lambda = r1.cwiseProduct(s.row_scale);
  return s;
}

double rel(const VectorXd& x, const VectorXd& y) {
  return (x - y).lpNorm<Eigen::Infinity>() / std::max(y.lpNorm<Eigen::Infinity>(), 1e-300);
}

// The nonzeros of each row of A, without the entry `skip_first` drops (to make grow() work).
std::vector<std::vector<int>> pattern_of(const MatrixXd& A, bool skip_first = false) {
  std::vector<std::vector<int>> rows(A.rows());
  for (int i = 0; i < A.rows(); ++i) {
    bool skipped = !skip_first;
    for (int j = 0; j < A.cols(); ++j)
      if (A(i, j) != 0) {
        if (!skipped) {
          skipped = true;
          continue;
        }
        rows[i].push_back(j);
      }
  }
  return rows;
}

// The mechanisms whose M may be definite (the Schur path): the shipped examples and the IFToMM
// N-four-bar for N = 1 .. 8. (The metamorphic generator's mechanisms have a singular M, massless
// node directions: none of 40 takes this path, they take the KKT path.)
std::vector<System> schur_mechanisms() {
  // qualified: in the unity build other tests' own double_fourbar() and fourbar() are visible
  namespace ex = mechanisms;
  std::vector<System> out = {ex::double_fourbar(),      ex::fourbar().system,
                             ex::whitworth().system,    ex::rrr3().system,
                             ex::slider_crank().system, ex::pendulum().system};
  for (int n = 1; n <= 8; ++n) out.push_back(bench::n_fourbar(n));
  return out;
}

// The structured solve against the dense one on the A, rhs, c of one evaluation of ForwardData,
// at 5 random moving states and efforts of each mechanism; 1e-12
// relative to the size of the terms (a = M^-1 rhs - M^-1 A^T lambda may cancel: its rounding is
// relative to the larger of the two, as lambda's is to |lambda|).
TEST(StructuredSchur, AccelerationsEqualTheDenseSchurSolve) {
  int checked = 0, mechanisms = 0;
  double worst = 0;
  for (const System& sys : schur_mechanisms()) {
    const Model m = build_model(sys);
    ForwardOptions o;
    o.linear_algebra = LinearAlgebra::dense;
    ForwardData d(m, o);
    if (!d.has_Minv || m.m1 == 0) continue;
    ++mechanisms;
    for (std::uint64_t seed = 1; seed <= 5; ++seed) {
      meta::Rng rng(seed);
      VectorXd q0 = m.q0, q1(m.n1);
      for (int k = 0; k < m.n1; ++k) q1[k] = rng.uniform(-1, 1);
      d.project(0, q0, q1, 1e-13 * m.scale, 1e-13);
      VectorXd u(m.n_inputs());
      for (int k = 0; k < m.n_inputs(); ++k) u[k] = rng.uniform(-1, 1);
      forward_accelerations(m, d, 0.1 * seed, q0, q1, u);  // A, rhs, c of this state
      const DenseSchur s = dense_schur(d.A, d.Minv, d.col_scale, d.rhs, d.c);
      if (!(s.ratio >= ForwardData::kDirectAccept)) continue;  // regularized: not this solve
      detail::StructuredSchur schur;
      schur.analyse(pattern_of(d.A), d.Minv);
      VectorXd row_scale(m.m1), r(m.m1), a(m.n1), lambda(m.m1);
      const double ratio = schur.factor(d.A, d.col_scale, row_scale);
      schur.solve(d.rhs, d.c, row_scale, r, a, lambda);
      EXPECT_EQ(row_scale, s.row_scale) << m.name;
      const VectorXd free = d.Minv * d.rhs, held = d.Minv * d.A.transpose() * s.lambda;
      const double scale = std::max({s.a.lpNorm<Eigen::Infinity>(), free.lpNorm<Eigen::Infinity>(),
                                     held.lpNorm<Eigen::Infinity>()});
      const double da = (a - s.a).lpNorm<Eigen::Infinity>() / scale;
      const double dl = rel(lambda, s.lambda);
      EXPECT_LE(da, 1e-12) << m.name << " state " << seed;
      EXPECT_LE(dl, 1e-12) << m.name << " state " << seed;
      EXPECT_NEAR(ratio, s.ratio, 1e-12 * s.ratio) << m.name;
      // ForwardData's own solve (its pattern checked entry by entry as A is written): the same
      // arithmetic as the StructuredSchur above, so the same bits
      EXPECT_EQ(d.a, a) << m.name << " state " << seed;
      worst = std::max({worst, da, dl});
      ++checked;
    }
  }
  EXPECT_GE(mechanisms, 9);
  EXPECT_GE(checked, 40);
  std::printf("structured vs dense Schur: %d mechanisms, %d states, worst %.2g\n", mechanisms,
              checked, worst);
}

// Random rows of 2 to 6 entries and a block-diagonal M^-1 (blocks of 1 to 4 variables): the
// ratio, a and lambda equal the dense solve's; a pattern missing one entry per row is found
// incomplete (covers) and grown to the same result.
TEST(StructuredSchur, RandomPatternsAndAGrownPattern) {
  meta::Rng rng(4242);
  double worst = 0;
  for (int trial = 0; trial < 50; ++trial) {
    const int n = rng.integer(4, 24), m = rng.integer(1, n - 1);
    MatrixXd Minv = MatrixXd::Zero(n, n);
    for (int k = 0; k < n;) {
      const int b = std::min(rng.integer(1, 4), n - k);
      MatrixXd R(b, b);
      for (int i = 0; i < b * b; ++i) R.data()[i] = rng.uniform(-1, 1);
      Minv.block(k, k, b, b) = R * R.transpose() + 0.5 * MatrixXd::Identity(b, b);
      k += b;
    }
    MatrixXd A = MatrixXd::Zero(m, n);
    for (int i = 0; i < m; ++i)
      for (int e = rng.integer(2, std::min(6, n)); e > 0; --e)
        A(i, rng.integer(0, n - 1)) = rng.uniform(-2, 2);
    VectorXd d(n), rhs(n), c(m);
    for (int k = 0; k < n; ++k) d[k] = rng.log_uniform(0.1, 10), rhs[k] = rng.uniform(-5, 5);
    for (int i = 0; i < m; ++i) c[i] = rng.uniform(-5, 5);
    const DenseSchur s = dense_schur(A, Minv, d, rhs, c);
    detail::StructuredSchur schur;
    schur.analyse(pattern_of(A, true), Minv);
    ASSERT_FALSE(schur.covers(A));
    schur.grow(pattern_of(A), Minv);
    ASSERT_TRUE(schur.covers(A));
    VectorXd row_scale(m), r(m), a(n), lambda(m);
    const double ratio = schur.factor(A, d, row_scale);
    if (s.ratio < 1e-12) {  // random rows may be dependent: both must say so
      EXPECT_LT(ratio, 1e-8) << trial;
      continue;
    }
    // L's diagonal carries a relative rounding error of about eps cond(G) = eps / ratio
    EXPECT_NEAR(ratio, s.ratio, 1e-10 * s.ratio + 1e-14) << trial;
    if (s.ratio < 1e-6) continue;  // the solve is only used from kDirectAccept = 1e-2
    schur.solve(rhs, c, row_scale, r, a, lambda);
    EXPECT_LE(rel(a, s.a), 1e-12) << trial;
    EXPECT_LE(rel(lambda, s.lambda), 1e-12) << trial;
    worst = std::max({worst, rel(a, s.a), rel(lambda, s.lambda)});
  }
  std::printf("structured vs dense Schur, random patterns: worst %.2g\n", worst);
}

// A random m x n A with rows of 2 to 6 entries.
MatrixXd random_rows(meta::Rng& rng, int m, int n) {
  MatrixXd A = MatrixXd::Zero(m, n);
  for (int i = 0; i < m; ++i)
    for (int e = rng.integer(2, std::min(6, n)); e > 0; --e)
      A(i, rng.integer(0, n - 1)) = rng.uniform(-2, 2);
  return A;
}

// The nonzeros of A outside `rows`, row by row; expects in_pattern to name exactly `rows`.
std::vector<std::vector<int>> outside_entries(const detail::StructuredSchur& schur,
                                              const MatrixXd& A,
                                              const std::vector<std::vector<int>>& rows) {
  std::vector<std::vector<int>> outside(A.rows());
  for (int i = 0; i < A.rows(); ++i)
    for (int j = 0; j < A.cols(); ++j) {
      const bool listed = std::find(rows[i].begin(), rows[i].end(), j) != rows[i].end();
      EXPECT_EQ(schur.in_pattern(i, j), listed) << "(" << i << ", " << j << ")";
      if (A(i, j) != 0 && !listed) outside[i].push_back(j);
    }
  return outside;
}

// The structured solve against the dense one where cond(G) <= 1e3 (they agree to about
// eps cond(G); the ratio of L's diagonal is only an estimate of 1 / cond(G)); a against the
// larger of its two terms (they may cancel). Returns whether it compared.
bool solves_agree(detail::StructuredSchur& schur, const MatrixXd& A, const MatrixXd& Minv) {
  const int m = static_cast<int>(A.rows()), n = static_cast<int>(A.cols());
  const VectorXd d = VectorXd::Ones(n), rhs = VectorXd::LinSpaced(n, -1, 1);
  const VectorXd c = VectorXd::LinSpaced(m, 1, 2);
  const DenseSchur s = dense_schur(A, Minv, d, rhs, c);
  const MatrixXd An = s.row_scale.asDiagonal() * A;
  const VectorXd ev =
      Eigen::SelfAdjointEigenSolver<MatrixXd>(An * Minv * An.transpose()).eigenvalues();
  VectorXd row_scale(m), r(m), a(n), lambda(m);
  if (!(schur.factor(A, d, row_scale) >= 1e-2) || !(ev[0] > 1e-3 * ev[m - 1])) return false;
  schur.solve(rhs, c, row_scale, r, a, lambda);
  const VectorXd free = Minv * rhs, held = Minv * A.transpose() * s.lambda;
  const double scale = std::max({s.a.lpNorm<Eigen::Infinity>(), free.lpNorm<Eigen::Infinity>(),
                                 held.lpNorm<Eigen::Infinity>()});
  EXPECT_LE((a - s.a).lpNorm<Eigen::Infinity>() / scale, 1e-12);
  EXPECT_LE(rel(lambda, s.lambda), 1e-12);
  return true;
}

// in_pattern (the check ForwardData makes as each entry of A is written) names exactly the
// entries analysed; an entry outside is found, and grow() by the entries written makes the
// pattern cover A, with the dense solve's result.
TEST(StructuredSchur, InPatternFindsAnEntryOutsideThePattern) {
  meta::Rng rng(77);
  int solved = 0;
  for (int trial = 0; trial < 30; ++trial) {
    SCOPED_TRACE(trial);
    const int n = rng.integer(4, 16), m = rng.integer(1, n - 1);
    const MatrixXd Minv = MatrixXd::Identity(n, n) * rng.uniform(0.5, 2);
    const MatrixXd A = random_rows(rng, m, n);
    const auto rows = pattern_of(A, true);  // one entry per row left out
    detail::StructuredSchur schur;
    schur.analyse(rows, Minv);
    const auto outside = outside_entries(schur, A, rows);
    ASSERT_FALSE(schur.covers(A));
    schur.grow(outside, Minv);
    ASSERT_TRUE(schur.covers(A));
    for (int i = 0; i < m; ++i)
      for (const int j : outside[i]) EXPECT_TRUE(schur.in_pattern(i, j));
    solved += solves_agree(schur, A, Minv) ? 1 : 0;
  }
  EXPECT_GE(solved, 5);
}

}  // namespace
}  // namespace mo2d
