// The sparse linear algebra of forward dynamics (sparse_engine.hpp).
#include "forward/sparse_engine.hpp"

#include <algorithm>
#include <cmath>

#include "constraints/constraints.hpp"
#include "dynamics/points.hpp"
#include "forward/least_squares.hpp"
#include "mo2d/dynamics.hpp"

namespace mo2d::detail {

using Eigen::VectorXd;

namespace {

// Sinks of the constraint rows into a row-major sparse matrix: an entry not yet in the pattern
// is inserted (the first fill, or a pattern that grows), the others only add to their value.
struct SparseVelSink {
  SparseRows& A;
  void add(int row, const VarRef& ref, double v) {
    if (ref.var >= 0) A.coeffRef(row, ref.var) += v;
  }
};
struct SparsePosSink {
  SparseRows& J;
  void add(int row, int var, double v) {
    if (var >= 0) J.coeffRef(row, var) += v;
  }
};
struct SparseSlotSink {
  SparseRows& A;
  const Model& m;
  std::vector<SlotEntry>& entries;
  void add(int row, const VarRef& ref, double v) {
    if (ref.var >= 0) A.coeffRef(row, ref.var) += v;
    if (ref.body >= 0 && ref.slot >= 0)
      entries.push_back({row, m.bodies[ref.body].offset + ref.slot, v});
  }
};

// zero the values, keep the pattern
void clear_values(SparseRows& J) {
  std::fill(J.valuePtr(), J.valuePtr() + J.nonZeros(), 0.0);
}

// compress after a fill; true when the fill inserted entries
bool settle(SparseRows& J) {
  if (J.isCompressed()) return false;
  J.makeCompressed();
  return true;
}

// index of C(r, c) in a compressed column-major C (the entry must exist)
int index_of(const SparseCols& C, int r, int c) {
  const int* begin = C.innerIndexPtr() + C.outerIndexPtr()[c];
  const int* end = C.innerIndexPtr() + C.outerIndexPtr()[c + 1];
  return static_cast<int>(std::lower_bound(begin, end, r) - C.innerIndexPtr());
}

// The mass matrix body by body (body_inertia of mo2d/dynamics.hpp for one body at a time: a body
// couples only the rates of its own nodes and its rotation), O(n) entries in O(n) time; the
// entries of a variable that two bodies share are summed.
SparseCols sparse_mass_matrix(const Model& m) {
  std::vector<Eigen::Triplet<double>> t;
  VectorXd e = VectorXd::Zero(m.n1);
  std::vector<int> vars;
  std::vector<double> l;
  for (const Body& b : m.bodies) {
    vars.clear();
    for (const NodeRef& n : b.nodes)
      if (n.var >= 0) vars.insert(vars.end(), {n.var, n.var + 1});
    if (b.omega.var >= 0) vars.push_back(b.omega.var);
    l.assign(b.slots(), 0.0);
    for (const int k : vars) {
      e[k] = 1;
      std::fill(l.begin(), l.end(), 0.0);
      const Vec2 acom = local_velocity_of_point(b, e, b.ci, b.cj, b.gamma, b.rho);
      add_point_force(b, b.ci, b.cj, b.gamma, b.rho, b.mass * acom, l.data());
      if (b.has_omega) l[b.slots() - 1] = b.inertia * omega_value(b.omega, e);
      e[k] = 0;
      for (const NodeRef& n : b.nodes) {
        if (n.var < 0) continue;
        t.emplace_back(n.var, k, l[2 * n.local]);
        t.emplace_back(n.var + 1, k, l[2 * n.local + 1]);
      }
      if (b.omega.var >= 0) t.emplace_back(b.omega.var, k, l[b.slots() - 1]);
    }
  }
  SparseCols M(m.n1, m.n1);
  M.setFromTriplets(t.begin(), t.end());
  M.prune(0.0);  // exact zeros of the probing (a node without mass) are not entries
  return M;
}

}  // namespace

void RowProduct::build(const SparseRows& J, const SparseCols& base) {
  const int n = static_cast<int>(J.cols());
  std::vector<Eigen::Triplet<double>> t;
  for (int c = 0; c < base.outerSize(); ++c)
    for (SparseCols::InnerIterator it(base, c); it; ++it)
      if (it.row() >= c) t.emplace_back(static_cast<int>(it.row()), c, 0.0);
  for (int i = 0; i < J.outerSize(); ++i)
    for (int a = J.outerIndexPtr()[i]; a < J.outerIndexPtr()[i + 1]; ++a)
      for (int b = J.outerIndexPtr()[i]; b < J.outerIndexPtr()[i + 1]; ++b)
        if (J.innerIndexPtr()[a] >= J.innerIndexPtr()[b])
          t.emplace_back(J.innerIndexPtr()[a], J.innerIndexPtr()[b], 0.0);
  for (int k = 0; k < n; ++k) t.emplace_back(k, k, 0.0);  // a definite diagonal is always stored
  C = SparseCols(n, n);
  C.setFromTriplets(t.begin(), t.end());
  C.makeCompressed();
  base_at.clear();
  for (int c = 0; c < base.outerSize(); ++c)
    for (SparseCols::InnerIterator it(base, c); it; ++it)
      base_at.push_back(it.row() >= c ? index_of(C, static_cast<int>(it.row()), c) : -1);
  pairs.clear();
  for (int i = 0; i < J.outerSize(); ++i)
    for (int a = J.outerIndexPtr()[i]; a < J.outerIndexPtr()[i + 1]; ++a)
      for (int b = J.outerIndexPtr()[i]; b < J.outerIndexPtr()[i + 1]; ++b)
        if (J.innerIndexPtr()[a] >= J.innerIndexPtr()[b])
          pairs.push_back({index_of(C, J.innerIndexPtr()[a], J.innerIndexPtr()[b]), a, b, i});
}

void RowProduct::fill(const SparseRows& J, const SparseCols& base, const VectorXd& w,
                      double scale) {
  double* v = C.valuePtr();
  std::fill(v, v + C.nonZeros(), 0.0);
  const double* bv = base.valuePtr();
  for (std::size_t k = 0; k < base_at.size(); ++k)
    if (base_at[k] >= 0) v[base_at[k]] += bv[k];
  const double* jv = J.valuePtr();
  for (const Pair& p : pairs) v[p.at] += scale * w[p.row] * jv[p.a] * jv[p.b];
}

void ColumnProduct::build(const SparseRows& J) {
  const int m = static_cast<int>(J.rows());
  // the entries of each column: (row, index in J's values)
  std::vector<std::vector<std::pair<int, int>>> cols(J.cols());
  for (int i = 0; i < m; ++i)
    for (int a = J.outerIndexPtr()[i]; a < J.outerIndexPtr()[i + 1]; ++a)
      cols[J.innerIndexPtr()[a]].emplace_back(i, a);
  std::vector<Eigen::Triplet<double>> t;
  t.reserve(static_cast<std::size_t>(m) + 4 * static_cast<std::size_t>(J.nonZeros()));
  for (int i = 0; i < m; ++i) t.emplace_back(i, i, 0.0);
  for (const auto& col : cols)
    for (const auto& [ra, a] : col)
      for (const auto& [rb, b] : col)
        if (ra >= rb) t.emplace_back(ra, rb, 0.0);
  C = SparseCols(m, m);
  C.setFromTriplets(t.begin(), t.end());
  C.makeCompressed();
  diag_at.resize(m);
  for (int i = 0; i < m; ++i) diag_at[i] = index_of(C, i, i);
  pairs.clear();
  for (int j = 0; j < static_cast<int>(cols.size()); ++j)
    for (const auto& [ra, a] : cols[j])
      for (const auto& [rb, b] : cols[j])
        if (ra >= rb) pairs.push_back({index_of(C, ra, rb), a, b, j, ra, rb});
}

void ColumnProduct::fill(const SparseRows& J, const VectorXd& w, const VectorXd& s) {
  double* v = C.valuePtr();
  std::fill(v, v + C.nonZeros(), 0.0);
  const double* jv = J.valuePtr();
  for (const Pair& p : pairs) v[p.at] += w[p.col] * s[p.ra] * jv[p.a] * s[p.rb] * jv[p.b];
}

SparseEngine::SparseEngine(const Model& m, const VectorXd& col_scale)
    : A(m.m1, m.n1), Psi(m.m0, m.n0), m_(m) {
  M = sparse_mass_matrix(m);
  M.makeCompressed();
  double dmd = 0;
  for (int k = 0; k < m.n1; ++k) dmd = std::max(dmd, M.coeff(k, k) * col_scale[k] * col_scale[k]);
  mass_scale = dmd > 0 ? dmd : 1.0;
  const double metric_floor = 1e-6 * mass_scale;
  // position metric: M's coordinate block plus metric_floor / d_k^2 on the diagonal (the dense
  // path's M0: massless nodes and extra coordinates held too)
  std::vector<Eigen::Triplet<double>> t;
  for (int c = 0; c < m.n0; ++c) {
    for (SparseCols::InnerIterator it(M, c); it; ++it)
      if (it.row() < m.n0) t.emplace_back(static_cast<int>(it.row()), c, it.value());
    t.emplace_back(c, c, metric_floor / (col_scale[c] * col_scale[c]));
  }
  M0 = SparseCols(m.n0, m.n0);
  M0.setFromTriplets(t.begin(), t.end());
  M0.makeCompressed();
  ones_m1_ = VectorXd::Ones(m.m1);
  ones_n1_ = VectorXd::Ones(m.n1);
  w_m_ = VectorXd::Zero(std::max(m.m0, m.m1));
  tmp_n_ = VectorXd::Zero(m.n1);
  tmp_n0_ = dq0_ = VectorXd::Zero(m.n0);
  tmp_m_ = VectorXd::Zero(m.m1);
  pos_row_scale_ = VectorXd::Ones(m.m0);
  pos_rhs_ = VectorXd::Zero(m.m0);
  A.reserve(Eigen::VectorXi::Constant(m.m1, 8));
  Psi.reserve(Eigen::VectorXi::Constant(m.m0, 8));
}

void SparseEngine::fill_velocity(const VectorXd& q0, double t, VectorXd& b) {
  clear_values(A);
  SparseVelSink sink{A};
  for (const auto& c : m_.constraints) velocity_rows(m_, c, q0, t, b, sink);
  if (settle(A)) ++pattern_A_;
}

void SparseEngine::fill_velocity_slots(const VectorXd& q0, double t, VectorXd& b,
                                       std::vector<SlotEntry>& entries) {
  clear_values(A);
  entries.clear();
  SparseSlotSink sink{A, m_, entries};
  for (const auto& c : m_.constraints) velocity_rows(m_, c, q0, t, b, sink);
  if (settle(A)) ++pattern_A_;
}

void SparseEngine::fill_position(const VectorXd& q0, double t, VectorXd& psi) {
  clear_values(Psi);
  SparsePosSink sink{Psi};
  for (const auto& c : m_.constraints)
    if (c.nrow0 > 0) position_rows(m_, c, q0, t, psi, sink);
  if (settle(Psi)) ++pattern_Psi_;
}

void SparseEngine::unit_row_scale(const SparseRows& J, const VectorXd& d, VectorXd& out) {
  for (int i = 0; i < J.outerSize(); ++i) {
    double s = 0;
    for (SparseRows::InnerIterator it(J, i); it; ++it) {
      const double x = it.value() * d[it.col()];
      s += x * x;
    }
    out[i] = s > 0 ? 1.0 / std::sqrt(s) : 1.0;
  }
}

// the products follow the pattern of A (a fill that inserted entries rebuilds them)
void SparseEngine::refresh_A() {
  if (version_A_ == pattern_A_) return;
  version_A_ = pattern_A_;
  build_kkt();
  H_.build(A, M);
  G_.build(A);
  R_.build(A);
  analysed_H_ = analysed_G_ = analysed_R_ = false;
}

void SparseEngine::build_kkt() {
  const int n1 = m_.n1, m1 = m_.m1;
  std::vector<Eigen::Triplet<double>> t;
  for (int c = 0; c < M.outerSize(); ++c)
    for (SparseCols::InnerIterator it(M, c); it; ++it)
      t.emplace_back(static_cast<int>(it.row()), c, 0.0);
  for (int i = 0; i < m1; ++i)
    for (SparseRows::InnerIterator it(A, i); it; ++it) {
      t.emplace_back(n1 + i, static_cast<int>(it.col()), 0.0);
      t.emplace_back(static_cast<int>(it.col()), n1 + i, 0.0);
    }
  kkt_ = SparseCols(n1 + m1, n1 + m1);
  kkt_.setFromTriplets(t.begin(), t.end());
  kkt_.makeCompressed();
  kkt_M_at_.clear();
  for (int c = 0; c < M.outerSize(); ++c)
    for (SparseCols::InnerIterator it(M, c); it; ++it)
      kkt_M_at_.push_back(index_of(kkt_, static_cast<int>(it.row()), c));
  kkt_A_at_.clear();
  kkt_At_at_.clear();
  for (int i = 0; i < m1; ++i)
    for (SparseRows::InnerIterator it(A, i); it; ++it) {
      kkt_A_at_.push_back(index_of(kkt_, n1 + i, static_cast<int>(it.col())));
      kkt_At_at_.push_back(index_of(kkt_, static_cast<int>(it.col()), n1 + i));
    }
  kkt_x_ = kkt_b_ = kkt_r_ = VectorXd::Zero(n1 + m1);
  lu_kkt_.reset();
}

bool SparseEngine::solve_kkt(const VectorXd& rhs, const VectorXd& c, const VectorXd& row_scale,
                             VectorXd& a, VectorXd& lambda) {
  refresh_A();
  const int n1 = m_.n1, m1 = m_.m1;
  double* v = kkt_.valuePtr();
  const double* mv = M.valuePtr();
  for (std::size_t k = 0; k < kkt_M_at_.size(); ++k) v[kkt_M_at_[k]] = mv[k];
  int k = 0;
  for (int i = 0; i < m1; ++i)
    for (int e = A.outerIndexPtr()[i]; e < A.outerIndexPtr()[i + 1]; ++e, ++k)
      v[kkt_A_at_[k]] = v[kkt_At_at_[k]] = row_scale[i] * A.valuePtr()[e];
  if (!lu_kkt_.factorize(kkt_)) return false;
  kkt_b_.head(n1) = rhs;
  kkt_b_.tail(m1) = c.cwiseProduct(row_scale);
  // Normwise backward error eta = |r| / (|K| |x| + |b|) of the solution, r = K x - b: one step of
  // iterative refinement where it is above 1e-14 (pivots reused from an earlier state may have
  // grown poor without the pivot ratio showing it); still above 1e-12, new pivots (once).
  double norm_K = 0;
  for (int c = 0; c < kkt_.outerSize(); ++c) {  // |K|_1 = |K|_inf: K is symmetric
    double col = 0;
    for (SparseCols::InnerIterator it(kkt_, c); it; ++it) col += std::abs(it.value());
    norm_K = std::max(norm_K, col);
  }
  auto eta = [&] {
    kkt_r_ = kkt_b_;
    kkt_r_.noalias() -= kkt_ * kkt_x_;
    return kkt_r_.lpNorm<Eigen::Infinity>() /
           (norm_K * kkt_x_.lpNorm<Eigen::Infinity>() + kkt_b_.lpNorm<Eigen::Infinity>());
  };
  for (int attempt = 0;; ++attempt) {
    kkt_x_ = kkt_b_;
    lu_kkt_.solve(kkt_x_);
    double e = eta();
    if (e > 1e-14 && std::isfinite(e)) {
      lu_kkt_.solve(kkt_r_);
      kkt_x_ += kkt_r_;
      e = eta();
    }
    if (kkt_x_.allFinite() && e <= 1e-12) break;
    if (attempt > 0 || !lu_kkt_.repivot(kkt_)) return false;
  }
  a = kkt_x_.head(n1);
  lambda = kkt_x_.tail(m1).cwiseProduct(row_scale);
  return true;
}

void SparseEngine::refresh_Psi() {
  if (version_Psi_ == pattern_Psi_) return;
  version_Psi_ = pattern_Psi_;
  W0_.build(Psi, M0);
  analysed_W0_ = false;
}

bool SparseEngine::factor_H(double alpha, const VectorXd& row_scale) {
  refresh_A();
  w_m_.head(m_.m1) = row_scale.cwiseAbs2();
  H_.fill(A, M, w_m_, alpha);
  if (!analysed_H_) llt_H_.analyse(H_.C), analysed_H_ = true;
  llt_H_.factorize_fixed(H_.C);
  return llt_H_.info() == Eigen::Success;
}

void SparseEngine::solve_H(VectorXd& x) {
  llt_H_.solve_in_place(x);
}

double SparseEngine::conditioning(const VectorXd& col_scale, const VectorXd& row_scale) {
  if (m_.m1 == 0) return 1.0;
  refresh_A();
  tmp_n_ = col_scale.cwiseAbs2();
  G_.fill(A, tmp_n_, row_scale);
  if (!analysed_G_) ldlt_G_.analyse(G_.C), analysed_G_ = true;
  ldlt_G_.factorize_fixed(G_.C);
  if (ldlt_G_.info() != Eigen::Success) return 0.0;
  const Eigen::VectorXd& D = ldlt_G_.diagonal();
  const double dmax = D.maxCoeff(), dmin = D.minCoeff();
  return dmax > 0 && dmin > 0 ? dmin / dmax : 0.0;
}

void SparseEngine::least_squares(const VectorXd& x, double eps, VectorXd& lambda) {
  refresh_A();
  R_.fill(A, ones_n1_, ones_m1_);
  double dmax = 1.0;
  for (int i = 0; i < m_.m1; ++i) dmax = std::max(dmax, R_.C.valuePtr()[R_.diag_at[i]]);
  for (int i = 0; i < m_.m1; ++i) R_.C.valuePtr()[R_.diag_at[i]] += eps * dmax;
  if (!analysed_R_) llt_R_.analyse(R_.C), analysed_R_ = true;
  llt_R_.factorize_fixed(R_.C);
  refined_least_squares(
      A, x, [this](VectorXd& v) { llt_R_.solve_in_place(v); }, lambda, tmp_n_, tmp_m_);
}

void SparseEngine::project_positions(double t, VectorXd& q0, double alpha,
                                     const VectorXd& pos_scale, double tol, VectorXd& psi) {
  if (m_.m0 == 0) return;
  constexpr int kSteps = 6;  // as projection_newton in forward_data.cpp
  for (int it = 1;; ++it) {
    fill_position(q0, t, psi);
    if (psi.lpNorm<Eigen::Infinity>() <= tol) return;
    refresh_Psi();
    unit_row_scale(Psi, pos_scale, pos_row_scale_);
    w_m_.head(m_.m0) = pos_row_scale_.cwiseAbs2();
    W0_.fill(Psi, M0, w_m_, alpha);
    if (!analysed_W0_) llt_W0_.analyse(W0_.C), analysed_W0_ = true;
    llt_W0_.factorize_fixed(W0_.C);
    // dx = alpha Psi^T P^2 psi solved with W0; q0 -= dx
    pos_rhs_ = psi.cwiseProduct(w_m_.head(m_.m0));
    tmp_n0_.noalias() = Psi.transpose() * pos_rhs_;
    tmp_n0_ *= alpha;
    dq0_ = tmp_n0_;
    llt_W0_.solve_in_place(dq0_);
    q0 -= dq0_;
    if (it == kSteps) return;  // the last iterate is not tested (the recorder judges the drift)
  }
}

}  // namespace mo2d::detail
