// Fixed-pattern LU of the inverse-dynamics samples (pattern_lu.hpp).
#include "linalg/pattern_lu.hpp"

#include <cmath>
#include <utility>

namespace mo2d::detail {

namespace {

const Eigen::VectorXd& no_scaling() {
  static const Eigen::VectorXd none;
  return none;
}

}  // namespace

PatternLU::PatternLU(int n, double dense_below)
    : n_(n), dense_below_(dense_below), dense_(n), scaled_(n, n), w_(n, n), outside_mask_(n, n) {
  const size_t nn = static_cast<size_t>(n) * n;
  outside_.assign(nn, ~uint64_t{0});
  lu_pattern_.assign(nn, 0);
  row_at_.resize(n);
  pos_.resize(n);
  swap_.resize(n);
  // capacities for every pattern: an analysis inside the per-sample loop allocates nothing
  for (auto* v :
       {&src_, &dst_, &row_, &col_, &fill_, &l_row_, &l_idx_, &u_col_, &uc_row_, &uc_idx_})
    v->reserve(nn);
  for (auto* v : {&l_start_, &u_start_, &uc_start_}) v->reserve(n + 1);
  swapped_.reserve(n);
}

double PatternLU::compute(const Eigen::Ref<const Eigen::MatrixXd>& A) {
  return compute_scaled(A, no_scaling(), no_scaling());
}

double PatternLU::compute_scaled(const Eigen::Ref<const Eigen::MatrixXd>& A,
                                 const Eigen::VectorXd& r, const Eigen::VectorXd& c) {
  const bool scale = r.size() > 0;
  bool analyse_next = !analysed_;
  if (analysed_ && !outside_pattern(A)) {
    double* w = w_.data();
    const double* a = A.data();
    for (const int f : fill_) w[f] = 0;
    const auto ne = static_cast<int>(src_.size());
    if (scale)
      for (int e = 0; e < ne; ++e) w[dst_[e]] = (r[row_[e]] * a[src_[e]]) * c[col_[e]];
    else
      for (int e = 0; e < ne; ++e) w[dst_[e]] = a[src_[e]];
    if (refactor()) {
      if (ratio_ >= dense_below_) {
        sparse_ = true;
        ++refactorizations;
        return ratio_;
      }
    } else {
      analyse_next = true;
    }
  } else {
    analyse_next = true;
  }
  // the dense partial-pivoting LU (the previous path), then a new analysis if the order failed
  if (scale)
    scaled_.noalias() = r.asDiagonal() * A * c.asDiagonal();
  else
    scaled_ = A;
  ratio_ = dense_.compute(scaled_);
  sparse_ = false;
  ++dense_factorizations;
  if (analyse_next) analyse(A);
  return ratio_;
}

bool PatternLU::outside_pattern(const Eigen::Ref<const Eigen::MatrixXd>& A) const {
  // sum |a_ij| over the entries outside the pattern (mask 1 there, 0 inside; a vectorized
  // product): 0 unless one is nonzero, non-finite if one is not finite (or one inside is
  // infinite: then the dense path, which reports it)
  double sum = 0;
  if (A.outerStride() == n_) {
    const auto nn = static_cast<Eigen::Index>(n_) * n_;
    sum = (Eigen::Map<const Eigen::ArrayXd>(A.data(), nn).abs() *
           Eigen::Map<const Eigen::ArrayXd>(outside_mask_.data(), nn))
              .sum();
  } else {
    sum = (A.array().abs() * outside_mask_.array()).sum();
  }
  return !(sum == 0);
}

bool PatternLU::refactor() {
  const int n = n_;
  double* a = w_.data();
  double umax = 0, umin = INFINITY;
  for (int k = 0; k < n; ++k) {
    const double pivot = a[k + k * n];
    if (pivot == 0 || !std::isfinite(pivot)) return false;
    umax = std::max(umax, std::abs(pivot));
    umin = std::min(umin, std::abs(pivot));
    const double inv = 1.0 / pivot;
    const int* l0 = l_row_.data() + l_start_[k];
    const int* l1 = l_row_.data() + l_start_[k + 1];
    double* lk = a + k * n;
    for (const int* p = l0; p != l1; ++p) {
      lk[*p] *= inv;
      if (!(std::abs(lk[*p]) <= 1)) return false;  // partial pivoting would choose row *p
    }
    for (int q = u_start_[k]; q < u_start_[k + 1]; ++q) {
      const int j = u_col_[q];
      const double akj = a[k + j * n];
      if (akj == 0) continue;
      double* col = a + j * n;
      for (const int* p = l0; p != l1; ++p) col[*p] -= lk[*p] * akj;
    }
  }
  ratio_ = n == 0 ? 1.0 : umin / umax;
  return true;
}

int PatternLU::det_sign() const {
  if (!sparse_) return dense_.det_sign();
  int sign = perm_sign_;
  for (int k = 0; k < n_; ++k) {
    const double u = w_(k, k);
    if (u == 0) return 0;
    if (u < 0) sign = -sign;
  }
  return sign;
}

void PatternLU::solve_in_place(Eigen::Ref<Eigen::VectorXd> xv) const {
  if (!sparse_) return dense_.solve_in_place(xv);
  const int n = n_;
  const double* a = w_.data();
  double* x = xv.data();
  const int *ls = l_start_.data(), *lr = l_row_.data(), *li = l_idx_.data();
  const int *us = uc_start_.data(), *ur = uc_row_.data(), *ui = uc_idx_.data();
  for (const int k : swapped_) std::swap(x[k], x[swap_[k]]);
  for (int j = 0; j < n; ++j) {  // L y = P b (unit lower)
    const double xj = x[j];
    if (xj != 0)
      for (int p = ls[j]; p < ls[j + 1]; ++p) x[lr[p]] -= a[li[p]] * xj;
  }
  for (int j = n - 1; j >= 0; --j) {  // U x = y
    x[j] /= a[j + j * n];
    const double xj = x[j];
    if (xj != 0)
      for (int p = us[j]; p < us[j + 1]; ++p) x[ur[p]] -= a[ui[p]] * xj;
  }
}

void PatternLU::solve_transpose_in_place(Eigen::Ref<Eigen::VectorXd> xv) const {
  if (!sparse_) return dense_.solve_transpose_in_place(xv);
  const int n = n_;
  const double* a = w_.data();
  double* x = xv.data();
  const int *ls = l_start_.data(), *lr = l_row_.data(), *li = l_idx_.data();
  const int *us = uc_start_.data(), *ur = uc_row_.data(), *ui = uc_idx_.data();
  for (int j = 0; j < n; ++j) {  // U^T y = b
    double s = x[j];
    for (int p = us[j]; p < us[j + 1]; ++p) s -= a[ui[p]] * x[ur[p]];
    x[j] = s / a[j + j * n];
  }
  for (int j = n - 1; j >= 0; --j) {  // L^T z = y (unit upper)
    double s = x[j];
    for (int p = ls[j]; p < ls[j + 1]; ++p) s -= a[li[p]] * x[lr[p]];
    x[j] = s;
  }
  for (auto k = swapped_.rbegin(); k != swapped_.rend(); ++k) std::swap(x[*k], x[swap_[*k]]);
}

// The pivot order of the dense factorization just computed (dense_), the pattern of A (grown by
// its nonzeros), and the symbolic elimination of that pattern in that order.
void PatternLU::analyse(const Eigen::Ref<const Eigen::MatrixXd>& A) {
  const int n = n_;
  ++analyses;
  swap_ = dense_.transpositions();
  perm_sign_ = 1;
  for (int k = 0; k < n; ++k) row_at_[k] = k;
  swapped_.clear();
  for (int k = 0; k < n; ++k)
    if (swap_[k] != k)
      std::swap(row_at_[k], row_at_[swap_[k]]), perm_sign_ = -perm_sign_, swapped_.push_back(k);
  for (int k = 0; k < n; ++k) pos_[row_at_[k]] = k;
  std::fill(lu_pattern_.begin(), lu_pattern_.end(), 0);
  src_.clear(), dst_.clear(), row_.clear(), col_.clear();
  for (int j = 0; j < n; ++j)
    for (int i = 0; i < n; ++i) {
      uint64_t& out = outside_[i + j * n];
      if (A(i, j) != 0) out = 0;  // (NaN too)
      if (out) continue;
      lu_pattern_[pos_[i] + j * n] = 1;
      src_.push_back(i + j * static_cast<int>(A.outerStride()));
      dst_.push_back(pos_[i] + j * n);
      row_.push_back(i);
      col_.push_back(j);
    }
  char* s = lu_pattern_.data();
  for (int k = 0; k < n; ++k) {  // symbolic elimination: the fill of L and U
    s[k + k * n] = 1;
    for (int j = k + 1; j < n; ++j)
      if (s[k + j * n])
        for (int i = k + 1; i < n; ++i)
          if (s[i + k * n]) s[i + j * n] = 1;
  }
  fill_.clear(), l_start_.clear(), l_row_.clear(), l_idx_.clear(), u_start_.clear(), u_col_.clear();
  uc_start_.clear(), uc_row_.clear(), uc_idx_.clear();
  for (int j = 0; j < n; ++j)
    for (int i = 0; i < n; ++i)
      if (s[i + j * n] && outside_[row_at_[i] + j * n] != 0) fill_.push_back(i + j * n);
  for (int k = 0; k < n; ++k) {
    l_start_.push_back(static_cast<int>(l_row_.size()));
    u_start_.push_back(static_cast<int>(u_col_.size()));
    uc_start_.push_back(static_cast<int>(uc_row_.size()));
    for (int i = k + 1; i < n; ++i)
      if (s[i + k * n]) l_row_.push_back(i), l_idx_.push_back(i + k * n);
    for (int j = k + 1; j < n; ++j)
      if (s[k + j * n]) u_col_.push_back(j);
    for (int i = 0; i < k; ++i)
      if (s[i + k * n]) uc_row_.push_back(i), uc_idx_.push_back(i + k * n);
  }
  l_start_.push_back(static_cast<int>(l_row_.size()));
  u_start_.push_back(static_cast<int>(u_col_.size()));
  uc_start_.push_back(static_cast<int>(uc_row_.size()));
  for (int k = 0; k < n * n; ++k) outside_mask_.data()[k] = outside_[k] != 0 ? 1.0 : 0.0;
  w_.setZero();
  analysed_ = true;
}

}  // namespace mo2d::detail
