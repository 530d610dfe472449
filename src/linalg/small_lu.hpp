#pragma once
// Dense LU with partial pivoting for the small systems of one sample (n ~ 10..40), unblocked:
// for these sizes Eigen's blocked PartialPivLU spends more time in panel bookkeeping than in
// arithmetic. Storage is allocated once (constructor); compute/solve never allocate.
#include <Eigen/Core>
#include <algorithm>
#include <cmath>
#include <utility>
#include <vector>

namespace mo2d::detail {

class SmallLU {
 public:
  SmallLU() = default;
  explicit SmallLU(int n) : lu_(n, n), perm_(n) {}

  // Factor P A = L U. Returns min|U_ii| / max|U_ii| (0 if singular): a cheap conditioning hint.
  double compute(const Eigen::Ref<const Eigen::MatrixXd>& A) {
    lu_ = A;
    const int n = static_cast<int>(lu_.rows());
    double* a = lu_.data();
    double umax = 0, umin = INFINITY;
    for (int k = 0; k < n; ++k) {
      int p = k;
      double best = std::abs(a[k + k * n]);
      for (int i = k + 1; i < n; ++i)
        if (std::abs(a[i + k * n]) > best) best = std::abs(a[i + k * n]), p = i;
      perm_[k] = p;
      if (p != k)
        for (int j = 0; j < n; ++j) std::swap(a[k + j * n], a[p + j * n]);
      const double pivot = a[k + k * n];
      umax = std::max(umax, std::abs(pivot));
      umin = std::min(umin, std::abs(pivot));
      if (pivot == 0) continue;
      const double inv = 1.0 / pivot;
      for (int i = k + 1; i < n; ++i) a[i + k * n] *= inv;
      for (int j = k + 1; j < n; ++j) {
        const double akj = a[k + j * n];
        if (akj == 0) continue;
        double* col = a + j * n;
        const double* lk = a + k * n;
        for (int i = k + 1; i < n; ++i) col[i] -= lk[i] * akj;
      }
    }
    ratio_ = n == 0 ? 1.0 : (umax > 0 ? umin / umax : 0.0);
    return ratio_;
  }
  double pivot_ratio() const { return ratio_; }
  // Sign of det A (+1, -1; 0 if singular): the orientation of A, which changes where a path of
  // matrices crosses a singular one.
  int det_sign() const {
    const int n = static_cast<int>(lu_.rows());
    int sign = 1;
    for (int k = 0; k < n; ++k) {
      if (perm_[k] != k) sign = -sign;
      const double u = lu_(k, k);
      if (u == 0) return 0;
      if (u < 0) sign = -sign;
    }
    return sign;
  }

  // x = A^-1 b, in place.
  void solve_in_place(Eigen::Ref<Eigen::VectorXd> x) const {
    const int n = static_cast<int>(lu_.rows());
    const double* a = lu_.data();
    for (int k = 0; k < n; ++k)
      if (perm_[k] != k) std::swap(x[k], x[perm_[k]]);
    for (int j = 0; j < n; ++j) {  // L y = P b (unit lower)
      const double xj = x[j];
      if (xj != 0)
        for (int i = j + 1; i < n; ++i) x[i] -= a[i + j * n] * xj;
    }
    for (int j = n - 1; j >= 0; --j) {  // U x = y
      x[j] /= a[j + j * n];
      const double xj = x[j];
      if (xj != 0)
        for (int i = 0; i < j; ++i) x[i] -= a[i + j * n] * xj;
    }
  }
  // x = A^-T b, in place: A^T = U^T L^T P.
  void solve_transpose_in_place(Eigen::Ref<Eigen::VectorXd> x) const {
    const int n = static_cast<int>(lu_.rows());
    const double* a = lu_.data();
    for (int j = 0; j < n; ++j) {  // U^T y = b (lower, column j of U is row j of U^T)
      double s = x[j];
      for (int i = 0; i < j; ++i) s -= a[i + j * n] * x[i];
      x[j] = s / a[j + j * n];
    }
    for (int j = n - 1; j >= 0; --j) {  // L^T z = y (unit upper)
      double s = x[j];
      for (int i = j + 1; i < n; ++i) s -= a[i + j * n] * x[i];
      x[j] = s;
    }
    for (int k = n - 1; k >= 0; --k)
      if (perm_[k] != k) std::swap(x[k], x[perm_[k]]);
  }
  const Eigen::MatrixXd& matrix() const { return lu_; }
  // the row transpositions of the last compute: step k swapped rows k and transpositions()[k]
  const std::vector<int>& transpositions() const { return perm_; }

 private:
  Eigen::MatrixXd lu_;
  std::vector<int> perm_;
  double ratio_ = 0;
};

}  // namespace mo2d::detail
