// The sparse kinematic set-up of large mechanisms (sparse_kinematics.hpp).
#include "kinematics/sparse_kinematics.hpp"

#include <Eigen/Eigenvalues>
#include <Eigen/SPQRSupport>
#include <Eigen/SparseCholesky>
#include <algorithm>
#include <cmath>
#include <cstdint>

#include "constraints/constraints.hpp"
#include "linalg/klu_lu.hpp"

namespace mo2d::detail {

using Eigen::VectorXd;
using SparseColsK = Eigen::SparseMatrix<double>;
using Triplets = std::vector<Eigen::Triplet<double>>;

namespace {

struct TripletPosSink {
  Triplets& t;
  const int* colmap;
  void add(int row, int var, double v) {
    const int c = colmap ? colmap[var] : var;
    if (c >= 0) t.emplace_back(row, c, v);
  }
};
struct TripletVelSink {
  Triplets& t;
  void add(int row, const VarRef& ref, double v) {
    if (ref.var >= 0) t.emplace_back(row, ref.var, v);
  }
};

// SuiteSparseQR (multifrontal, rank-revealing by Heath's method: a column whose remaining norm is
// below the threshold is dead, permuted to the end). Eigen's own SparseQR was tried first: 90 %
// of a 0.43 s build_model at N = 400 (N-four-bar), growing as N^1.8.
using QR = Eigen::SPQR<SparseColsK>;

// The QR of B^T with the absolute pivot threshold (B has unit rows, so B^T has unit columns and
// the threshold is relative to them, as the dense QR's is to its largest pivot).
void factor_transpose(const SparseRowsK& B, double threshold, QR& qr) {
  SparseColsK Bt = B.transpose();  // row-major B viewed as column-major B^T: a copy
  Bt.makeCompressed();
  qr.setPivotThreshold(threshold);
  qr.compute(Bt);
}

}  // namespace

void sparse_position_jacobian(const Model& m, const VectorXd& q0, double t, const int* colmap,
                              int cols, VectorXd& psi, SparseRowsK& J) {
  Triplets tr;
  tr.reserve(8 * static_cast<std::size_t>(m.m0));
  TripletPosSink sink{tr, colmap};
  for (const auto& c : m.constraints)
    if (c.nrow0 > 0) position_rows(m, c, q0, t, psi, sink);
  J.resize(m.m0, cols);
  J.setFromTriplets(tr.begin(), tr.end());
}

void sparse_velocity_jacobian(const Model& m, const VectorXd& q0, double t, SparseRowsK& A,
                              VectorXd& b) {
  Triplets tr;
  tr.reserve(8 * static_cast<std::size_t>(m.m1));
  TripletVelSink sink{tr};
  for (const auto& c : m.constraints) velocity_rows(m, c, q0, t, b, sink);
  A.resize(m.m1, m.n1);
  A.setFromTriplets(tr.begin(), tr.end());
}

void make_dimensionless(SparseRowsK& J, const VectorXd& d) {
  for (int i = 0; i < J.outerSize(); ++i) {
    double s = 0;
    for (SparseRowsK::InnerIterator it(J, i); it; ++it) {
      it.valueRef() *= d[it.col()];
      s += it.value() * it.value();
    }
    if (s > 0)
      for (SparseRowsK::InnerIterator it(J, i); it; ++it) it.valueRef() /= std::sqrt(s);
  }
}

std::vector<int> sparse_dependent_rows(const SparseRowsK& B, double threshold) {
  std::vector<int> out;
  if (B.rows() == 0) return out;
  QR qr;
  factor_transpose(B, threshold, qr);
  const auto perm = qr.colsPermutation();  // a map of SPQR's E (the object holds the pointer)
  for (int k = static_cast<int>(qr.rank()); k < B.rows(); ++k)
    out.push_back(static_cast<int>(perm.indices()[k]));
  return out;
}

bool sparse_minimum_norm_step(const SparseRowsK& J, const VectorXd& psi, double threshold,
                              VectorXd& dx) {
  // J^T P = Q R: J = P R^T Q^T, and J dx = psi with dx = Q [y; 0] is R11^T y = (P^T psi)_1 on
  // the rank leading rows; the other rows depend on them (consistent) or are dropped
  QR qr;
  factor_transpose(J, threshold, qr);
  if (qr.info() != Eigen::Success) return false;
  const int r = static_cast<int>(qr.rank());
  const VectorXd p = qr.colsPermutation().transpose() * psi;
  VectorXd y = VectorXd::Zero(J.cols());
  using SparseR = Eigen::SparseMatrix<double, Eigen::ColMajor, SuiteSparse_long>;
  const SparseR R = qr.matrixR().topLeftCorner(r, r);
  y.head(r) = R.transpose().triangularView<Eigen::Lower>().solve(p.head(r));
  dx = qr.matrixQ() * y;
  return dx.allFinite();
}

namespace {

struct SparseAssembly {
  const Model& m;
  double t;
  const std::vector<int>& colmap;
  int nfree;
  VectorXd& psi;
  SparseRowsK J;
  VectorXd dx, trial;

  void evaluate(const VectorXd& q) {
    sparse_position_jacobian(m, q, t, colmap.data(), nfree, psi, J);
  }
  bool step() {
    double scale = 0;
    for (int i = 0; i < J.outerSize(); ++i) scale = std::max(scale, J.row(i).norm());
    return sparse_minimum_norm_step(J, psi, 1e-12 * std::max(scale, 1e-300), dx);
  }
  // Armijo backtracking from the whole step; psi and J at the accepted point (or, stalled, at q)
  bool search(VectorXd& q, double& err) {
    const double norm2 = psi.norm();
    for (double alpha = 1; alpha >= 1e-8; alpha *= 0.5) {
      trial = q;
      for (int k = 0; k < m.n0; ++k)
        if (colmap[k] >= 0) trial[k] -= alpha * dx[colmap[k]];
      evaluate(trial);
      if (psi.allFinite() && psi.norm() <= (1 - 1e-4 * alpha) * norm2) {
        err = psi.lpNorm<Eigen::Infinity>();
        q.swap(trial);
        return true;
      }
    }
    evaluate(q);
    return false;
  }
};

}  // namespace

SparseNewton sparse_assembly_newton(const Model& m, double tolerance, double t,
                                    const std::vector<int>& colmap, int nfree, VectorXd& q,
                                    VectorXd& psi) {
  constexpr int kMaxIterations = 100;
  SparseAssembly s{m, t, colmap, nfree, psi, {}, {}, {}};
  s.evaluate(q);
  if (!psi.allFinite()) return SparseNewton::non_finite;
  double err = psi.lpNorm<Eigen::Infinity>();
  for (int it = 1;; ++it) {
    if (err <= tolerance) return SparseNewton::converged;
    if (it > kMaxIterations) return SparseNewton::max_iterations;
    if (!s.step()) return SparseNewton::stalled;
    if (!s.search(q, err)) return SparseNewton::stalled;
    if (it == kMaxIterations) return SparseNewton::max_iterations;
  }
}

double sparse_lu_solve(const SparseColsK& K, const VectorXd& rhs, VectorXd& x) {
  KluLU lu;
  if (!lu.factorize(K)) return 0.0;
  x = rhs;
  lu.solve(x);
  return lu.pivot_ratio();
}

namespace {

// The largest eigenvalue of a symmetric operator (x -> apply(x)) of size n: Lanczos with full
// reorthogonalization from a pseudo-random start (a structured one, all ones, can be orthogonal to
// the eigenvector of a symmetric chain), until the Ritz value's residual |beta_j s_j| is below
// 1e-8 of it (its error is at most that, about its square over the gap to the next) or 300 steps.
template <class Apply>
double lanczos_largest(int n, Apply&& apply) {
  const int kmax = std::min(n, 300);
  Eigen::MatrixXd V(n, kmax);
  VectorXd alpha(kmax), beta(kmax), w(n);
  std::uint64_t seed = 0x9E3779B97F4A7C15ULL;
  for (int i = 0; i < n; ++i) {
    seed = seed * 6364136223846793005ULL + 1442695040888963407ULL;
    V(i, 0) = 0.5 + static_cast<double>(seed >> 11) * 0x1.0p-53;
  }
  V.col(0).normalize();
  double theta = 0;
  for (int j = 0; j < kmax; ++j) {
    apply(V.col(j), w);
    alpha[j] = V.col(j).dot(w);
    for (int pass = 0; pass < 2; ++pass)  // full reorthogonalization, twice
      w.noalias() -= V.leftCols(j + 1) * (V.leftCols(j + 1).transpose() * w);
    beta[j] = w.norm();
    // every 10 steps the Ritz values alone (O(j^2)); the residual (eigenvectors, O(j^3)) once the
    // largest has stopped moving
    const bool last = j + 1 == kmax || !(beta[j] > 0);
    if (last || (j + 1) % 10 == 0) {
      Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> t;
      t.computeFromTridiagonal(alpha.head(j + 1), beta.head(j), Eigen::EigenvaluesOnly);
      const double next = t.eigenvalues()[j];
      const bool settled = std::abs(next - theta) <= 1e-10 * std::abs(next);
      theta = next;
      if (last) break;
      if (settled) {
        t.computeFromTridiagonal(alpha.head(j + 1), beta.head(j), Eigen::ComputeEigenvectors);
        if (beta[j] * std::abs(t.eigenvectors()(j, j)) <= 1e-8 * std::abs(theta)) break;
      }
    }
    V.col(j + 1) = w / beta[j];
  }
  return theta;
}

// Largest eigenvalue of the symmetric positive semi-definite G (lower triangle stored).
double largest_eigenvalue(const SparseColsK& G) {
  return lanczos_largest(static_cast<int>(G.rows()), [&](const auto& x, VectorXd& y) {
    y.noalias() = G.selfadjointView<Eigen::Lower>() * x;
  });
}

// Smallest eigenvalue of the symmetric positive definite G: the largest of G^-1 by its LDL^T;
// 0 if G is singular.
double smallest_eigenvalue(const SparseColsK& G) {
  Eigen::SimplicialLDLT<SparseColsK, Eigen::Lower> ldlt(G);
  if (ldlt.info() != Eigen::Success || !(ldlt.vectorD().minCoeff() > 0)) return 0.0;
  const double inv = lanczos_largest(static_cast<int>(G.rows()),
                                     [&](const auto& x, VectorXd& y) { y = ldlt.solve(x); });
  return inv > 0 ? 1 / inv : 0.0;
}

}  // namespace

SparseSingular sparse_extreme_singular_values(const SparseRowsK& B, double rank_threshold) {
  SparseSingular s;
  if (B.rows() == 0 || B.cols() == 0) return s;
  const int k = static_cast<int>(std::min(B.rows(), B.cols()));
  QR qr;
  factor_transpose(B, rank_threshold, qr);
  s.rank = static_cast<int>(qr.rank());
  // the Gram matrix of the shorter side: its eigenvalues are the squared singular values
  const SparseColsK Bc = B;
  const SparseColsK G =
      B.rows() <= B.cols() ? SparseColsK(Bc * Bc.transpose()) : SparseColsK(Bc.transpose() * Bc);
  const SparseColsK lower = G.triangularView<Eigen::Lower>();
  s.sigma_max = std::sqrt(largest_eigenvalue(lower));
  s.sigma_min = s.rank < k ? 0.0 : std::sqrt(smallest_eigenvalue(lower));
  return s;
}

}  // namespace mo2d::detail
