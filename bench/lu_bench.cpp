// The LU of one inverse-dynamics sample, alone: the dimensionless K = [A; E] of the Whitworth
// (12 x 12) and 3RRR (22 x 22) at t = 1 s of their reference runs, factored and used for the five
// solves of a sample (q1, a1, the dof columns of C; here always five), by
//   dense:   SmallLU (dense partial pivoting; the path before the fixed-pattern LU),
//   pattern: PatternLU (src/linalg/pattern_lu.hpp: the pivot order of the first call, numeric
//            refactorization of the nonzeros only),
//   klu:     SuiteSparse KLU through KluLU (klu_refactor with the first call's pivots, klu_rcond,
//            klu_solve), the values copied into the compressed matrix each time.
// docs/performance.md ("Issue 14 targets (≤ 2 µs ...)") reports them.
#include <benchmark/benchmark.h>

#include <Eigen/SparseCore>
#include <vector>

#include "linalg/klu_lu.hpp"
#include "linalg/pattern_lu.hpp"
#include "linalg/small_lu.hpp"
#include "mo2d/inverse.hpp"
#include "mo2d/mechanisms.hpp"
#include "mo2d/model.hpp"

namespace {

using mo2d::mechanisms::Example;
using Factory = Example (*)();

// Ks after the samples of the reference run up to t = 1 s.
Eigen::MatrixXd scaled_K(Factory make) {
  const Example ex = make();
  const mo2d::Model model = mo2d::build_model(ex.system);
  mo2d::InverseData d(model, ex.motion, ex.run);
  const int N = ex.run.samples;
  for (int k = 0; k < N; ++k) {
    const double t = ex.run.t0 + (ex.run.t1 - ex.run.t0) * k / (N - 1);
    if (t > 1) break;
    mo2d::inverse_dynamics_sample(model, d, t);
  }
  return d.k_row.asDiagonal() * d.K * d.col_scale.asDiagonal();
}

Eigen::VectorXd rhs(int n) {
  return Eigen::VectorXd::LinSpaced(n, 1.0, 2.0);
}

void BM_LU_dense(benchmark::State& state, Factory make) {
  const Eigen::MatrixXd Ks = scaled_K(make);
  const int n = static_cast<int>(Ks.rows());
  mo2d::detail::SmallLU lu(n);
  Eigen::VectorXd x(n);
  const Eigen::VectorXd b = rhs(n);
  for (auto _ : state) {
    benchmark::DoNotOptimize(lu.compute(Ks));
    for (int s = 0; s < 5; ++s) x = b, lu.solve_in_place(x);
    benchmark::DoNotOptimize(x.data());
  }
}

void BM_LU_pattern(benchmark::State& state, Factory make) {
  const Eigen::MatrixXd Ks = scaled_K(make);
  const int n = static_cast<int>(Ks.rows());
  mo2d::detail::PatternLU lu(n);
  Eigen::VectorXd x(n);
  const Eigen::VectorXd b = rhs(n);
  for (auto _ : state) {
    benchmark::DoNotOptimize(lu.compute(Ks));
    for (int s = 0; s < 5; ++s) x = b, lu.solve_in_place(x);
    benchmark::DoNotOptimize(x.data());
  }
  state.counters["sparse"] = static_cast<double>(lu.refactorizations);
}

void BM_LU_klu(benchmark::State& state, Factory make) {
  const Eigen::MatrixXd Ks = scaled_K(make);
  const int n = static_cast<int>(Ks.rows());
  Eigen::SparseMatrix<double> S = Ks.sparseView();
  S.makeCompressed();
  std::vector<int> at;  // dense index of each stored value
  for (int j = 0; j < n; ++j)
    for (Eigen::SparseMatrix<double>::InnerIterator it(S, j); it; ++it)
      at.push_back(it.row() + j * n);
  mo2d::detail::KluLU lu;
  Eigen::VectorXd x(n);
  const Eigen::VectorXd b = rhs(n);
  for (auto _ : state) {
    for (size_t e = 0; e < at.size(); ++e) S.valuePtr()[e] = Ks.data()[at[e]];
    benchmark::DoNotOptimize(lu.factorize(S));
    for (int s = 0; s < 5; ++s) x = b, lu.solve(x);
    benchmark::DoNotOptimize(x.data());
  }
  state.counters["refactor"] = static_cast<double>(lu.refactorizations);
}

}  // namespace

BENCHMARK_CAPTURE(BM_LU_dense, whitworth, &mo2d::mechanisms::whitworth);
BENCHMARK_CAPTURE(BM_LU_pattern, whitworth, &mo2d::mechanisms::whitworth);
BENCHMARK_CAPTURE(BM_LU_klu, whitworth, &mo2d::mechanisms::whitworth);
BENCHMARK_CAPTURE(BM_LU_dense, rrr3, &mo2d::mechanisms::rrr3);
BENCHMARK_CAPTURE(BM_LU_pattern, rrr3, &mo2d::mechanisms::rrr3);
BENCHMARK_CAPTURE(BM_LU_klu, rrr3, &mo2d::mechanisms::rrr3);
