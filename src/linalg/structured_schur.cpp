// The Schur complement along the structure of A (structured_schur.hpp).
#include "linalg/structured_schur.hpp"

#include <algorithm>
#include <cmath>

namespace mo2d::detail {

using Eigen::MatrixXd;
using Eigen::VectorXd;

namespace {

// the columns of the nonzeros of each row of the symmetric M^-1, and their values
void minv_rows(const MatrixXd& Minv, std::vector<int>& ptr, std::vector<int>& col,
               std::vector<double>& val) {
  ptr.assign(1, 0);
  col.clear();
  val.clear();
  for (int k = 0; k < Minv.rows(); ++k) {
    for (int l = 0; l < Minv.cols(); ++l)
      if (Minv(k, l) != 0) {
        col.push_back(l);
        val.push_back(Minv(k, l));
      }
    ptr.push_back(static_cast<int>(col.size()));
  }
}

}  // namespace

void StructuredSchur::analyse(const std::vector<std::vector<int>>& rows, const MatrixXd& Minv) {
  m_ = static_cast<int>(rows.size());
  n_ = static_cast<int>(Minv.rows());
  rows_ = rows;
  row_ptr_.assign(1, 0);
  col_.clear();
  for (auto& r : rows_) {
    std::sort(r.begin(), r.end());
    r.erase(std::unique(r.begin(), r.end()), r.end());
    col_.insert(col_.end(), r.begin(), r.end());
    row_ptr_.push_back(static_cast<int>(col_.size()));
  }
  an_.assign(col_.size(), 0.0);
  lin_.resize(col_.size());
  in_.assign(static_cast<std::size_t>(m_) * n_, 0);
  for (int i = 0; i < m_; ++i)
    for (int a = row_ptr_[i]; a < row_ptr_[i + 1]; ++a) {
      lin_[a] = i + col_[a] * m_;
      in_[lin_[a]] = 1;
    }
  minv_rows(Minv, minv_ptr_, minv_col_, minv_val_);
  // P's pattern, row by row, and the products that make its entries; pos[i][l]: index of P(i, l)
  std::vector<std::vector<int>> pos(m_, std::vector<int>(n_, -1));
  p_ptr_.assign(1, 0);
  p_col_.clear();
  p_terms_.clear();
  for (int i = 0; i < m_; ++i) {
    std::vector<int> cols;
    for (int a = row_ptr_[i]; a < row_ptr_[i + 1]; ++a)
      for (int v = minv_ptr_[col_[a]]; v < minv_ptr_[col_[a] + 1]; ++v)
        cols.push_back(minv_col_[v]);
    std::sort(cols.begin(), cols.end());
    cols.erase(std::unique(cols.begin(), cols.end()), cols.end());
    for (const int l : cols) {
      pos[i][l] = static_cast<int>(p_col_.size());
      p_col_.push_back(l);
    }
    p_ptr_.push_back(static_cast<int>(p_col_.size()));
    for (int a = row_ptr_[i]; a < row_ptr_[i + 1]; ++a)
      for (int v = minv_ptr_[col_[a]]; v < minv_ptr_[col_[a] + 1]; ++v)
        p_terms_.push_back({pos[i][minv_col_[v]], a, v});
  }
  p_.assign(p_col_.size(), 0.0);
  // G(i, j) = P_i . (N A)_j over the columns the two rows share (only those pairs)
  g_terms_.clear();
  for (int i = 0; i < m_; ++i)
    for (int j = 0; j <= i; ++j)
      for (int a = row_ptr_[j]; a < row_ptr_[j + 1]; ++a)
        if (const int p = pos[i][col_[a]]; p >= 0) g_terms_.push_back({i + j * m_, p, a});
  L_ = MatrixXd::Zero(m_, m_);
}

bool StructuredSchur::covers(const MatrixXd& A) const {
  Eigen::Index in_pattern = 0;
  for (int i = 0; i < m_; ++i)
    for (int a = row_ptr_[i]; a < row_ptr_[i + 1]; ++a) in_pattern += A(i, col_[a]) != 0;
  return in_pattern == (A.array() != 0).count();
}

void StructuredSchur::grow(const std::vector<std::vector<int>>& extra, const MatrixXd& Minv) {
  std::vector<std::vector<int>> rows = rows_;
  for (int i = 0; i < m_; ++i) rows[i].insert(rows[i].end(), extra[i].begin(), extra[i].end());
  analyse(rows, Minv);
}

double StructuredSchur::factor(const MatrixXd& A, const VectorXd& col_scale, VectorXd& row_scale) {
  const double* A_data = A.data();
  for (int a = 0; a < static_cast<int>(lin_.size()); ++a) an_[a] = A_data[lin_[a]];
  for (int i = 0; i < m_; ++i) {  // N: unit rows of A D (as detail::unit_row_scale)
    double s = 0;
    for (int a = row_ptr_[i]; a < row_ptr_[i + 1]; ++a) {
      const double x = an_[a] * col_scale[col_[a]];
      s += x * x;
    }
    const double n = s > 0 ? 1.0 / std::sqrt(s) : 1.0;
    row_scale[i] = n;
    for (int a = row_ptr_[i]; a < row_ptr_[i + 1]; ++a) an_[a] *= n;
  }
  std::fill(p_.begin(), p_.end(), 0.0);
  for (const PTerm& t : p_terms_) p_[t.p_at] += an_[t.a] * minv_val_[t.v];
  L_.setZero();
  double* g = L_.data();
  for (const GTerm& t : g_terms_) g[t.g_at] += p_[t.p] * an_[t.a];
  if (!cholesky()) return 0;
  if (m_ == 0) return 1;
  const auto d = L_.diagonal();
  const double dmax = d.maxCoeff(), dmin = d.minCoeff();
  return (dmin / dmax) * (dmin / dmax);
}

// G = L L^T in place (left-looking by columns, skipping the zeros of L); false where a pivot is
// not positive (or not finite).
bool StructuredSchur::cholesky() {
  double* l = L_.data();
  for (int j = 0; j < m_; ++j) {
    double* cj = l + j * m_;
    for (int k = 0; k < j; ++k) {
      const double ljk = l[j + k * m_];
      if (ljk == 0) continue;
      const double* ck = l + k * m_;
      for (int i = j; i < m_; ++i) cj[i] -= ck[i] * ljk;
    }
    if (!(cj[j] > 0) || !std::isfinite(cj[j])) return false;
    const double djj = std::sqrt(cj[j]);
    cj[j] = djj;
    const double inv = 1.0 / djj;
    for (int i = j + 1; i < m_; ++i) cj[i] *= inv;
  }
  return true;
}

void StructuredSchur::solve(const VectorXd& rhs, const VectorXd& c, const VectorXd& row_scale,
                            VectorXd& r, VectorXd& a, VectorXd& lambda) const {
  for (int i = 0; i < m_; ++i) {  // r = P rhs - N c
    double s = -c[i] * row_scale[i];
    for (int p = p_ptr_[i]; p < p_ptr_[i + 1]; ++p) s += p_[p] * rhs[p_col_[p]];
    r[i] = s;
  }
  const double* l = L_.data();
  for (int j = 0; j < m_; ++j) {  // L y = r
    const double* cj = l + j * m_;
    r[j] /= cj[j];
    const double yj = r[j];
    if (yj != 0)
      for (int i = j + 1; i < m_; ++i) r[i] -= cj[i] * yj;
  }
  for (int j = m_ - 1; j >= 0; --j) {  // L^T lambda_n = y
    const double* cj = l + j * m_;
    double s = r[j];
    for (int i = j + 1; i < m_; ++i) s -= cj[i] * r[i];
    r[j] = s / cj[j];
  }
  for (int k = 0; k < n_; ++k) {  // a = M^-1 rhs - P^T lambda_n
    double s = 0;
    for (int v = minv_ptr_[k]; v < minv_ptr_[k + 1]; ++v) s += minv_val_[v] * rhs[minv_col_[v]];
    a[k] = s;
  }
  for (int i = 0; i < m_; ++i)
    for (int p = p_ptr_[i]; p < p_ptr_[i + 1]; ++p) a[p_col_[p]] -= p_[p] * r[i];
  for (int i = 0; i < m_; ++i) lambda[i] = r[i] * row_scale[i];
}

}  // namespace mo2d::detail
