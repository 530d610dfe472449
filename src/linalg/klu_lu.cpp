// Sparse LU by SuiteSparse's KLU (klu_lu.hpp).
#include "linalg/klu_lu.hpp"

#include <klu.h>

namespace mo2d::detail {

struct KluLU::Impl {
  klu_common common{};
  klu_symbolic* symbolic = nullptr;
  klu_numeric* numeric = nullptr;
  double rcond_full = 0;  // klu_rcond after the last full factorization
  Impl() { klu_defaults(&common); }
  void free_numeric() {
    if (numeric) klu_free_numeric(&numeric, &common);
  }
  void free_all() {
    free_numeric();
    if (symbolic) klu_free_symbolic(&symbolic, &common);
  }
};

namespace {

int* cols(const Eigen::SparseMatrix<double>& A) {
  return const_cast<int*>(A.outerIndexPtr());  // NOLINT(cppcoreguidelines-pro-type-const-cast)
}
int* rows(const Eigen::SparseMatrix<double>& A) {
  return const_cast<int*>(A.innerIndexPtr());  // NOLINT(cppcoreguidelines-pro-type-const-cast)
}
double* values(const Eigen::SparseMatrix<double>& A) {
  return const_cast<double*>(A.valuePtr());  // NOLINT(cppcoreguidelines-pro-type-const-cast)
}

}  // namespace

KluLU::KluLU() : p_(new Impl) {}

KluLU::~KluLU() {
  p_->free_all();
  delete p_;
}

void KluLU::reset() {
  p_->free_all();
}

bool KluLU::repivot(const Eigen::SparseMatrix<double>& A) {
  p_->free_numeric();
  if (!p_->symbolic)
    p_->symbolic = klu_analyze(static_cast<int>(A.rows()), cols(A), rows(A), &p_->common);
  if (!p_->symbolic) return false;
  p_->numeric = klu_factor(cols(A), rows(A), values(A), p_->symbolic, &p_->common);
  ++full_factorizations;
  if (!p_->numeric || p_->common.status != KLU_OK) return false;
  klu_rcond(p_->symbolic, p_->numeric, &p_->common);
  p_->rcond_full = p_->common.rcond;
  return p_->rcond_full > 0;
}

bool KluLU::factorize(const Eigen::SparseMatrix<double>& A) {
  if (!p_->numeric) return repivot(A);
  ++refactorizations;
  if (!klu_refactor(cols(A), rows(A), values(A), p_->symbolic, p_->numeric, &p_->common) ||
      p_->common.status != KLU_OK)
    return repivot(A);
  klu_rcond(p_->symbolic, p_->numeric, &p_->common);
  if (!(p_->common.rcond >= 1e-3 * p_->rcond_full)) return repivot(A);
  return true;
}

double KluLU::pivot_ratio() const {
  return p_->numeric ? p_->common.rcond : 0.0;
}

void KluLU::solve(Eigen::VectorXd& x) {
  klu_solve(p_->symbolic, p_->numeric, static_cast<int>(x.size()), 1, x.data(), &p_->common);
}

}  // namespace mo2d::detail
